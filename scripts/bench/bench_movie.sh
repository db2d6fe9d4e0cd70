#!/usr/bin/env bash
# bench_movie.sh: a trajectory movie made by `movie make` on 1, 2 and 4 MPI ranks, with its
# phase times (the paper's Table 3: script loading, state loading, geometry and rendering,
# total), frames per minute and parallel efficiency; then the state loading of N ranks
# every one reading the files against rank 0 reading and broadcasting.
#
#   scripts/bench/bench_movie.sh [-a natoms] [-f frames] [-s WxH] [-r "1 2 4"] [-rep style]
#
# The system: tests/data/1tii.pdb replicated on a lattice to natoms (default 100,000) by
# scripts/bench/replicate.py, and a 100-frame DCD made from it by molscope (every frame the
# structure breathing about its centre by up to 3 %), both in bench-out/. The movie: one
# frame per trajectory frame, NewCartoon coloured by structure (the cartoon is rebuilt for
# every frame), render snapshot at 1280x720, an MP4 encoded as the frames complete.
# Loading uses `bcast on` (MOLSCOPE_NOBCAST=1 for the every-rank-reads runs).
set -eu
srcdir=$(cd "$(dirname "$0")/../.." && pwd)
molscope=${MOLSCOPE:-$srcdir/src/molscope}
natoms=100000 frames=100 size=1280x720 ranks="1 2 4" rep="NewCartoon 0.3 10 4.1 0"
while [ $# -gt 0 ]; do
    case $1 in
        -a) natoms=$2; shift 2;; -f) frames=$2; shift 2;; -s) size=$2; shift 2;;
        -r) ranks=$2; shift 2;; -rep) rep=$2; shift 2;;
        *) echo "usage: $0 [-a natoms] [-f frames] [-s WxH] [-r \"1 2 4\"] [-rep style]" >&2; exit 2;;
    esac
done
w=${size%x*} h=${size#*x}
out=$srcdir/bench-out
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export MOLSCOPE_TCLLIB=${MOLSCOPE_TCLLIB:-$srcdir/tcl}

sys=$out/movie_sys_$natoms.pdb traj=$out/movie_traj_$natoms.dcd
[ -f "$sys" ] || /usr/bin/python3 "$srcdir/scripts/bench/replicate.py" \
    "$srcdir/tests/data/1tii.pdb" "$natoms" "$sys" >/dev/null
if [ ! -f "$traj" ]; then
    cat > "$out/movie_gen.tcl" <<'TCL'
lassign $argv sys traj
mol new $sys waitfor all
set c [measure center [atomselect top all]]
for {set f 1} {$f < 100} {incr f} {
    animate dup top
    set k [expr {1.0 + 0.03 * sin(2 * acos(-1) * $f / 100.0)}]
    set a [atomselect top all frame $f]
    $a moveby [vecscale -1 $c]
    $a move [list [list $k 0 0 0] [list 0 $k 0 0] [list 0 0 $k 0] {0 0 0 1}]
    $a moveby $c
    $a delete
}
animate write dcd $traj beg 0 end -1 waitfor all
quit
TCL
    "$molscope" -dispdev text -e "$out/movie_gen.tcl" -args "$sys" "$traj" </dev/null >/dev/null
fi

cat > "$out/movie_bench.tcl" <<'TCL'
lassign $argv sys traj dir frames w h rep
mol new $sys waitfor all bcast on
mol addfile $traj waitfor all bcast on
mol modstyle 0 top {*}$rep
mol modcolor 0 top Structure
set r [movie make -basename $dir/f -video $dir/movie.mp4 -type trajectory -frames $frames \
           -size $w $h]
if {[parallel noderank] == 0} { puts "RESULT $r" }
quit
TCL

# run NP DIR FRAMES [env...]: one job in a clean folder; prints its RESULT dict and the wall
# time. run_again: the same in the folder as it is.
run() { rm -rf "$2"; run_again "$@"; }
run_again() {
    local np=$1 dir=$2 nf=$3; shift 3
    local t0=$EPOCHREALTIME
    local line
    line=$(mpirun -np "$np" "$@" "$molscope" -dispdev text -e "$out/movie_bench.tcl" \
        -args "$sys" "$traj" "$dir" "$nf" "$w" "$h" "$rep" </dev/null 2>"$dir.log" |
        tr -d '\r' | grep '^RESULT')
    echo "${line#RESULT } wall $(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN{printf "%.2f", b - a}')"
}
get() { awk -v k="$2" '{for (i = 1; i < NF; i += 2) if ($i == k) print $(i + 1)}' <<< "$1"; }

natoms_real=$(grep -c '^ATOM\|^HETATM' "$sys")
echo "movie: $frames-frame trajectory of $natoms_real atoms ($(du -m "$traj" | cut -f1) MB DCD), ${w}x$h, $rep, render snapshot, MP4"
printf '%-6s %9s %9s %10s %11s %10s %9s %11s %9s %10s\n' ranks "wall (s)" "script" "state" \
    "geom+rend" "total" "fr/min" efficiency "busy max" "enc tail"
t1=
for n in $ranks; do
    r=$(run "$n" "$out/movie_$n" "$frames")
    render=$(get "$r" render)
    [ -z "$t1" ] && t1=$render && n1=$n
    eff=$(awk -v a="$t1" -v b="$render" -v n="$n" -v n1="$n1" 'BEGIN{printf "%.2f", a * n1 / (b * n)}')
    fpm=$(awk -v f="$(get "$r" rendered)" -v t="$render" 'BEGIN{printf "%.1f", f * 60 / t}')
    frames_ok=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
        -of csv=p=0 "$out/movie_$n/movie.mp4" 2>/dev/null || echo "?")
    printf '%-6s %9s %4.2f/%4.2f %5.2f/%4.2f %11.2f %10.2f %9s %11s %9.2f %10.2f  (video: %s frames)\n' \
        "$n" "$(get "$r" wall)" "$(get "$r" script)" "$(get "$r" script_max)" "$(get "$r" state)" \
        "$(get "$r" state_max)" "$render" "$(get "$r" total)" "$fpm" "$eff" "$(get "$r" busy_max)" \
        "$(get "$r" encode_tail)" "$frames_ok"
done
echo "(script and state: rank 0 / slowest rank; efficiency: geometry+rendering on the first row's ranks x its ranks / (this row's x its ranks))"

# The encoder alone: the same job again finds every frame and only encodes.
n=${ranks%% *}
r=$(run_again "$n" "$out/movie_$n" "$frames")
echo "encoding only (every frame there, $n rank(s)): $(get "$r" encode_tail) s for $frames frames, $(awk -v f="$frames" -v t="$(get "$r" encode_tail)" 'BEGIN{printf "%.1f", f / t}') frames/s (PNG read back + ffmpeg libx264 veryfast at ${w}x$h)"

echo
echo "state loading (mol new + mol addfile of the PDB and the DCD, rank 0 / slowest rank, s), a 4-frame movie:"
printf '%-6s %22s %22s\n' ranks "every rank reads" "rank 0 reads, bcast"
for n in $ranks; do
    a=$(run "$n" "$out/movie_load" 4 -x MOLSCOPE_NOBCAST=1)
    b=$(run "$n" "$out/movie_load" 4)
    printf '%-6s %11.2f / %-8.2f %11.2f / %-8.2f\n' "$n" "$(get "$a" state)" "$(get "$a" state_max)" \
        "$(get "$b" state)" "$(get "$b" state_max)"
done
echo "($(nproc) cores; $(mpirun --version | head -1); load average $(cut -d' ' -f1-3 /proc/loadavg))"
rm -rf "$out"/movie_[0-9]* "$out"/movie_load "$out"/movie_*.log
