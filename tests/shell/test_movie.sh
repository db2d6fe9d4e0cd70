# test_movie.sh: `movie make` as a job: a 20-frame movie of 1tii in one process and under
# mpirun with 2 ranks gives the same frames, pixel for pixel (PIL), with both ranks
# rendering; the video has every frame, in order (each decoded video frame is nearest its
# own PNG); progress and phase times on rank 0 only; a job killed with SIGKILL midway and
# run again renders only the missing frames and completes (every frame a whole PNG,
# ffprobe counts 20 frames, no temporary file left); frames only ever appear under their
# final names by a rename of a complete file (strace); renderer choice; a failing frame on
# one rank ends the job with its message; no ffmpeg: frames and a clear message.
. "$(dirname "$0")/lib.sh"
D=$MS_TEST_DATA
mpi_job_setup
PY=/usr/bin/python3
have_pil=0; $PY -c 'import PIL, numpy' 2>/dev/null && have_pil=1
have_ff=0; command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null && have_ff=1
have_mpi=0
if command -v mpirun >/dev/null &&
   [ "$(echo 'puts [parallel nodecount]' | timeout 60 mpirun -np 2 $M 2>/dev/null | tr -d '\r' | grep -c '^2$')" = 2 ]; then
    have_mpi=1
fi
# mpi NP ARGS...: mpirun with a limit, so a hang fails instead of stopping the suite (its
# ranks write through a terminal: drop the carriage returns).
mpi() { local np=$1; shift; timeout 120 mpirun -np "$np" "$@" | tr -d '\r'; return "${PIPESTATUS[0]}"; }
nframes() { ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1" 2>&1; }

echo 'if {[catch {render snapshot probe.png} msg]} { puts "NOGL $msg" }' > probe.tcl
if $M -e probe.tcl </dev/null 2>&1 | grep -q NOGL; then
    skip "movie" "render snapshot does not work here"; rm -rf "$scratch"; exit 0
fi

# The movie: 20 frames of 1tii turning about y; the user proc logs which rank renders what.
cat > movie.tcl <<'TCL'
lassign $argv dir video
mol new $env(MS_TEST_DATA)/1tii.pdb
mol modstyle 0 0 Licorice 0.3 8 8
proc logrank {i} {
    set f [open $::dir/ranks.log a]; puts $f "$i [parallel noderank]"; close $f
    if {[info exists ::env(SLOW)]} { after $::env(SLOW) }
}
set o [list -basename $dir/f -type {rotation user} -proc logrank -frames 20 -size 160 120]
if {$video ne ""} { lappend o -video $video }
set r [movie make {*}$o]
if {[parallel noderank] == 0} { puts "RESULT $r" }
TCL
mkdir -p one two
out1=$($M -e movie.tcl -args one one/m.mp4 </dev/null 2>one.err); rc1=$?
expect_eq "one process: the movie is made" "$rc1:$(printf '%s\n' "$out1" | grep '^RESULT' | grep -o 'rendered [0-9]* reused [0-9]*')" \
    "0:rendered 20 reused 0"
expect_eq "one process: 20 frames, no temporary file" "$(ls one | grep -c '^f\.[0-9]\{5\}\.png$'):$(ls one | grep -c 'part\|\.tmp')" "20:0"
if [ $have_mpi = 1 ]; then
    out2=$(mpi 2 $M -e movie.tcl -args two two/m.mp4 </dev/null 2>two.err); rc2=$?
    expect_eq "2 ranks: the movie is made" "$rc2:$(printf '%s\n' "$out2" | grep '^RESULT' | grep -o 'rendered [0-9]* reused [0-9]* ranks [0-9]*')" \
        "0:rendered 20 reused 0 ranks 2"
    expect_eq "2 ranks: every frame rendered exactly once" "$(awk '{print $1}' two/ranks.log | sort -n | tr '\n' ' ')" \
        "$(seq 0 19 | tr '\n' ' ')"
    expect_eq "2 ranks: both ranks rendered frames" "$(awk '{print $2}' two/ranks.log | sort -u | tr '\n' ' ')" "0 1 "
    if [ $have_pil = 1 ]; then
        res=$($PY - <<'PY'
from PIL import Image
import numpy as np
bad = []
for i in range(20):
    a = np.asarray(Image.open("one/f.%05d.png" % i).convert("RGB"))
    b = np.asarray(Image.open("two/f.%05d.png" % i).convert("RGB"))
    if a.shape != (120, 160, 3) or a.shape != b.shape or (a != b).any(): bad.append(i)
print("differ:", bad)
PY
)
        expect_eq "1 process and 2 ranks: the 20 frames are equal pixel for pixel" "$res" "differ: []"
    else
        same=0; for i in $(seq -f %05g 0 19); do cmp -s one/f.$i.png two/f.$i.png && same=$((same + 1)); done
        expect_eq "1 process and 2 ranks: the 20 frames are the same files (no PIL here)" "$same" 20
    fi
    expect_eq "2 ranks: progress and phase times from rank 0 only" \
        "$(grep -c 'movie: 20/20 frames' two.err):$(grep -c 'movie: phases (rank 0 / slowest rank): script loading' two.err)" "1:1"
else
    skip "mpi" "no mpirun, or molscope is built without MPI"
fi
expect_match "progress: frames done of total, frames per minute, time left" "$(grep 'movie: 20/20' one.err)" \
    "movie: 20/20 frames, *[0-9].[0-9] frames/min, 0:00 left"
expect_match "phase times of the paper's Table 3" "$(grep 'movie: phases' one.err)" \
    "movie: phases (rank 0 / slowest rank): script loading *s, state loading *s, geometry and rendering *s, total *s"

if [ $have_ff = 1 ]; then
    expect_eq "video: ffprobe counts 20 frames (one process)" "$(nframes one/m.mp4)" 20
    [ $have_mpi = 1 ] && expect_eq "video: ffprobe counts 20 frames (2 ranks)" "$(nframes two/m.mp4)" 20
    if [ $have_pil = 1 ]; then
        # in_order DIR: the decoded frames of DIR/m.mp4 that are not nearest their own PNG
        in_order() {
            ffmpeg -v error -i "$1/m.mp4" -f rawvideo -pix_fmt rgb24 - | $PY -c '
import sys, numpy as np
from PIL import Image
d = sys.argv[1]
v = np.frombuffer(sys.stdin.buffer.read(), np.uint8).reshape(-1, 120, 160, 3).astype(float)
f = [np.asarray(Image.open("%s/f.%05d.png" % (d, i)).convert("RGB"), float) for i in range(20)]
print("out of order:", [k for k in range(len(v)) if min(range(20), key=lambda i: np.abs(v[k] - f[i]).mean()) != k])' "$1"
        }
        expect_eq "video: each decoded frame is nearest its own PNG (one process)" "$(in_order one)" "out of order: []"
        [ $have_mpi = 1 ] && expect_eq "video: ... and with 2 ranks finishing frames out of order" \
            "$(in_order two)" "out of order: []"
    fi
else
    skip "video" "no ffmpeg/ffprobe"
fi

# ---------------------------------------------------------------- killed and run again
if [ $have_mpi = 1 ]; then run_job() { mpi 2 $M -e movie.tcl -args "$@"; }; else run_job() { $M -e movie.tcl -args "$@"; }; fi
mkdir -p kill
SLOW=150 run_job kill kill/m.mp4 </dev/null >/dev/null 2>&1 &
job=$!
for t in $(seq 1 300); do
    [ "$(ls kill 2>/dev/null | grep -c '^f\.[0-9]*\.png$')" -ge 6 ] && break
    sleep 0.05
done
# SIGKILL every molscope process of the job (found by pid among the job's descendants).
descendants() { local c; for c in $(ps -o pid= --ppid "$1"); do echo "$c"; descendants "$c"; done; }
for p in $(descendants "$job"); do [ "$(ps -o comm= -p "$p")" = molscope ] && kill -9 "$p"; done
wait "$job" 2>/dev/null
sleep 0.3
before=$(ls kill | grep -c '^f\.[0-9]*\.png$')
expect_eq "kill -9 midway: some frames exist, not all" "$([ "$before" -ge 6 ] && [ "$before" -lt 20 ] && echo yes)" yes
out=$(run_job kill kill/m.mp4 </dev/null 2>/dev/null); rc=$?
expect_eq "run again: only the missing frames are rendered" \
    "$rc:$(printf '%s\n' "$out" | grep '^RESULT' | grep -o 'rendered [0-9]* reused [0-9]*')" "0:rendered $((20 - before)) reused $before"
if [ $have_pil = 1 ]; then
    res=$($PY - <<'PY'
from PIL import Image
bad = []
for i in range(20):
    try:
        im = Image.open("kill/f.%05d.png" % i); im.load()
        if im.size != (160, 120): bad.append(i)
    except Exception:
        bad.append(i)
print("invalid:", bad)
PY
)
    expect_eq "run again: every frame is a whole 160x120 image" "$res" "invalid: []"
fi
expect_eq "run again: the frames equal the uninterrupted movie's" \
    "$(for i in $(seq -f %05g 0 19); do cmp -s one/f.$i.png kill/f.$i.png || echo "$i"; done | wc -l)" 0
expect_eq "run again: no temporary file is left" "$(ls kill | grep -c 'part\|\.tmp')" 0
[ $have_ff = 1 ] && expect_eq "run again: the video plays, ffprobe counts 20 frames" "$(nframes kill/m.mp4)" 20

# ---------------------------------------------------------------- temporary names only
if command -v strace >/dev/null && strace -f -o /dev/null true 2>/dev/null; then
    mkdir -p st
    strace -f -e trace=openat,open,creat,rename,renameat,renameat2 -o st.log \
        $M -e movie.tcl -args st </dev/null >/dev/null 2>&1
    final='st/f\.[0-9]{5}\.png"'
    expect_eq "strace: no final frame name is ever opened for writing" \
        "$(grep -E "open.*$final.*O_(WRONLY|RDWR|CREAT)" st.log | wc -l)" 0
    expect_eq "strace: every final frame name is made by one rename of its temporary file" \
        "$(grep -E "rename.*st/f\.[0-9]{5}\.tmp-[A-Za-z0-9]{8}\.png\", .*$final" st.log | grep -c '= 0$')" 20
else
    skip "strace" "strace is not there or cannot trace here"
fi

# ---------------------------------------------------------------- renderer choice
if command -v tachyon >/dev/null; then
    cat > tach.tcl <<'TCL'
mol new $env(MS_TEST_DATA)/1tii.pdb
set r [movie make -basename tach/f -renderer tachyon -frames 2 -size 96 64 -progress off]
puts "R [dict get $r rendered] [::molscope::movie::frameok tach/f.00001.png 96 64]"
TCL
    expect_eq "-renderer Tachyon: frames ray traced by the tachyon program" \
        "$($M -e tach.tcl </dev/null 2>&1 | grep '^R'):$(ls tach | tr '\n' ' ')" "R 2 1:f.00000.png f.00001.png "
    if [ $have_pil = 1 ]; then
        echo 'mol new $env(MS_TEST_DATA)/1tii.pdb; movie make -basename snap/f -frames 2 -size 96 64 -progress off' > snap.tcl
        $M -e snap.tcl </dev/null >/dev/null 2>&1
        res=$($PY -c '
from PIL import Image
import numpy as np
a = np.asarray(Image.open("tach/f.00001.png").convert("RGB"), float)
b = np.asarray(Image.open("snap/f.00001.png").convert("RGB"), float)
print("differ" if np.abs(a - b).mean() > 0.5 else "same")')
        expect_eq "-renderer Tachyon and snapshot give different images" "$res" differ
    fi
else
    skip "tachyon" "no tachyon program"
fi

# ---------------------------------------------------------------- errors in a job
if [ $have_mpi = 1 ]; then
    cat > fail.tcl <<'TCL'
mol new $env(MS_TEST_DATA)/1tii.pdb
proc p {i} { after 20; if {$i == 5} { error "frame five cannot be drawn" } }
movie make -basename fail/f -type user -proc p -frames 12 -size 32 24 -progress off
puts never
TCL
    out=$(mpi 2 $M -e fail.tcl </dev/null 2>&1); rc=$?
    expect_match "a frame failing on one rank ends the job with its message" "$rc:$out" \
        "[1-9]*movie make: frame 5: frame five cannot be drawn*"
    expect_eq "... no rank goes on" "$(printf '%s\n' "$out" | grep -c '^never')" 0
fi
out=$(MOLSCOPE_FFMPEG=/nonexistent/ffmpeg $M -e movie.tcl -args noff noff/m.mp4 </dev/null 2>&1)
expect_match "no ffmpeg: a clear message, and frames only" "$out:$(ls noff | grep -c '^f.*png$'):$(ls noff | grep -c mp4)" \
    "*movie: no video: MOLSCOPE_FFMPEG=/nonexistent/ffmpeg is not there*:20:0"
rm -rf "$scratch"
