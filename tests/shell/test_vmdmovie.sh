# test_vmdmovie.sh: a MovieMaker script (the ::MovieMaker:: variables and a user frame proc
# attached to ::MovieMaker::userframe with a write trace, as VMD documents) under mpirun with
# 2 ranks makes the same frames, pixel for pixel, as `movie make` with the same frame
# procedure in one process; both ranks render; the video has every frame. Then a killed-
# and-rerun MovieMaker job renders only the missing frames (resume), and a rotation movie
# under 2 ranks equals the one-process `movie make -type rotation`.
. "$(dirname "$0")/lib.sh"
mpi_job_setup
PY=/usr/bin/python3
echo 'if {[catch {render snapshot probe.png} msg]} { puts "NOGL $msg" }' > probe.tcl
if $M -e probe.tcl </dev/null 2>&1 | grep -q NOGL; then
    skip "vmdmovie" "render snapshot does not work here"; rm -rf "$scratch"; exit 0
fi
if ! command -v mpirun >/dev/null ||
   [ "$(echo 'puts [parallel nodecount]' | timeout 60 mpirun -np 2 $M 2>/dev/null | tr -d '\r' | grep -c '^2$')" != 2 ]; then
    skip "vmdmovie mpi" "no mpirun, or molscope is built without MPI"; rm -rf "$scratch"; exit 0
fi
mpi() { local np=$1; shift; timeout 120 mpirun -np "$np" "$@" | tr -d '\r'; return "${PIPESTATUS[0]}"; }
have_ff=0; command -v ffprobe >/dev/null && command -v ffmpeg >/dev/null && have_ff=1

# The scene both scripts share: 1tii in licorice, 12 frames; frame i turns the starting view
# about y by 30 i and about x by 5 i (set from i alone, as a frame procedure must be).
cat > scene.tcl <<'TCL'
mol new $env(MS_TEST_DATA)/1tii.pdb
mol modstyle 0 0 Licorice 0.3 8 8
display resize 120 90
set pose0 [::molscope::movie::pose]
proc setframe {i} {
    ::molscope::movie::pose $::pose0
    rotate y by [expr {30 * $i}]
    rotate x by [expr {5 * $i}]
    set f [open $::env(LOG) a]; puts $f "$i [parallel noderank]"; close $f
}
TCL
cat > mm.tcl <<'TCL'
source scene.tcl
package require vmdmovie
proc moviecallback {args} { setframe $::MovieMaker::userframe }
trace add variable ::MovieMaker::userframe write moviecallback
set ::MovieMaker::movietype userdefined
set ::MovieMaker::workdir [lindex $argv 0]
set ::MovieMaker::basename mm
set ::MovieMaker::framerate 24
set ::MovieMaker::movieduration 0.5
set ::MovieMaker::movieformat imgif
set ::MovieMaker::cleanfiles 0
set r [::MovieMaker::buildmovie]
if {[parallel noderank] == 0} { puts "RESULT $r numframes $::MovieMaker::numframes" }
TCL
cat > mk.tcl <<'TCL'
source scene.tcl
set r [movie make -basename [lindex $argv 0]/mm -type user -proc setframe -frames 12 -size 120 90 -progress off]
puts "RESULT $r"
TCL
mkdir -p mpi one
out2=$(LOG=$scratch/mpi.log mpi 2 $M -e mm.tcl -args mpi </dev/null 2>mpi.err); rc2=$?
expect_eq "MovieMaker script on 2 ranks: 12 frames made" \
    "$rc2:$(printf '%s\n' "$out2" | grep '^RESULT' | grep -o 'rendered [0-9]* reused [0-9]* ranks [0-9]*'):$(printf '%s\n' "$out2" | grep '^RESULT' | grep -o 'numframes [0-9]*')" \
    "0:rendered 12 reused 0 ranks 2:numframes 12"
expect_eq "2 ranks: the user frame proc ran once per frame" "$(awk '{print $1}' mpi.log | sort -n | tr '\n' ' ')" \
    "$(seq 0 11 | tr '\n' ' ')"
expect_eq "2 ranks: both ranks rendered frames" "$(awk '{print $2}' mpi.log | sort -u | tr '\n' ' ')" "0 1 "
out1=$(LOG=$scratch/one.log $M -e mk.tcl -args one </dev/null 2>one.err); rc1=$?
expect_eq "movie make in one process: 12 frames" "$rc1:$(printf '%s\n' "$out1" | grep '^RESULT' | grep -o 'rendered [0-9]* reused [0-9]* ranks [0-9]*')" \
    "0:rendered 12 reused 0 ranks 1"
same=0; for i in $(seq -f %05g 0 11); do cmp -s one/mm.$i.png mpi/mm.$i.png && same=$((same + 1)); done
expect_eq "MovieMaker on 2 ranks and movie make in one process: the same 12 frames" "$same" 12
diff=0; for i in 00001 00002; do cmp -s mpi/mm.00000.png mpi/mm.$i.png || diff=$((diff + 1)); done
expect_eq "the frames differ from each other" "$diff" 2
if [ $have_ff = 1 ]; then
    expect_eq "the animated GIF has the 12 frames" \
        "$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=codec_name,nb_read_frames -of csv=p=0 mpi/mm.gif | tr -d ,)" "gif12"
fi

# Resume: frames lost from a MovieMaker movie are the only ones rendered again.
rm -f mpi/mm.00003.png mpi/mm.00010.png mpi.log
out3=$(LOG=$scratch/mpi.log mpi 2 $M -e mm.tcl -args mpi </dev/null 2>>mpi.err)
expect_eq "rerun on 2 ranks: only the 2 missing frames are rendered" \
    "$(printf '%s\n' "$out3" | grep '^RESULT' | grep -o 'rendered [0-9]* reused [0-9]*'):$(awk '{print $1}' mpi.log | sort -n | tr '\n' ' ')" \
    "rendered 2 reused 10:3 10 "
same=0; for i in 00003 00010; do cmp -s one/mm.$i.png mpi/mm.$i.png && same=$((same + 1)); done
expect_eq "rerun: the re-rendered frames are the same" "$same" 2

# A rotation movie: MovieMaker on 2 ranks equals `movie make -type rotation` in one process.
cat > rot.tcl <<'TCL'
mol new $env(MS_TEST_DATA)/1tii.pdb
display resize 100 80
if {[lindex $argv 1] eq "mm"} {
    package require vmdmovie
    set ::MovieMaker::movietype rotation
    set ::MovieMaker::workdir [lindex $argv 0]
    set ::MovieMaker::basename r
    set ::MovieMaker::rotateangle 360
    set ::MovieMaker::movieduration 0.5
    set ::MovieMaker::movieformat pngframes
    ::MovieMaker::buildmovie
} else {
    movie make -basename [lindex $argv 0]/r -type rotation -angle 360 -frames 12 -progress off
}
TCL
mkdir -p rmpi rone
mpi 2 $M -e rot.tcl -args rmpi mm </dev/null >/dev/null 2>&1
$M -e rot.tcl -args rone mk </dev/null >/dev/null 2>&1
same=0; for i in $(seq -f %05g 0 11); do cmp -s rone/r.$i.png rmpi/r.$i.png && same=$((same + 1)); done
expect_eq "rotation: MovieMaker on 2 ranks equals movie make -type rotation, 12 frames" "$same:$(ls rmpi | wc -l)" "12:12"
rm -rf "$scratch"
