#!/usr/bin/env bash
# bench_stream.sh: a movie over a trajectory larger than a memory budget, with its frames all
# in memory (VMD's way) and streamed (molscope's -stream, here chosen by the budget itself):
# the peak resident memory (VmHWM) and the time per movie frame, wall and CPU, with the
# default threads and with one (MOLSCOPE_THREADS=1).
#
#   scripts/bench/bench_stream.sh [-a natoms] [-f frames] [-s WxH] [-b budget]
#
# The system: tests/data/1tii.pdb replicated to natoms (default 100,000) by replicate.py,
# and a DCD of `frames` frames (default 200; 12 bytes an atom a frame, so 240 MB at the
# defaults) made by molscope, every frame the structure shifted a little, both in
# bench-out/. The movie: `movie make -type trajectory` over every frame,
# Lines, TachyonInternal at WxH (default 160x90). The budget (MOLSCOPE_TRAJ_BUDGET, default
# 100M) is below the trajectory's size, so the second run streams.
set -eu
srcdir=$(cd "$(dirname "$0")/../.." && pwd)
molscope=${MOLSCOPE:-$srcdir/src/molscope}
natoms=100000 frames=200 size=160x90 budget=100M
while [ $# -gt 0 ]; do
    case $1 in
        -a) natoms=$2; shift 2;; -f) frames=$2; shift 2;; -s) size=$2; shift 2;;
        -b) budget=$2; shift 2;;
        *) echo "usage: $0 [-a natoms] [-f frames] [-s WxH] [-b budget]" >&2; exit 2;;
    esac
done
w=${size%x*} h=${size#*x}
out=$srcdir/bench-out
mkdir -p "$out"
export MOLSCOPE_TCLLIB=${MOLSCOPE_TCLLIB:-$srcdir/tcl}

sys=$out/stream_sys_$natoms.pdb traj=$out/stream_traj_${natoms}_$frames.dcd
[ -f "$sys" ] || /usr/bin/python3 "$srcdir/scripts/bench/replicate.py" \
    "$srcdir/tests/data/1tii.pdb" "$natoms" "$sys" >/dev/null
if [ ! -f "$traj" ]; then
    cat > "$out/stream_gen.tcl" <<'TCL'
lassign $argv sys traj frames
mol new $sys waitfor all
for {set k 1} {$k < $frames} {incr k} {
    animate dup top
    set a [atomselect top all frame $k]
    $a moveby [list [expr {0.5 * sin($k / 7.0)}] [expr {0.5 * cos($k / 5.0)}] 0]
    $a delete
}
animate write dcd $traj waitfor all
quit
TCL
    "$molscope" -dispdev text -e "$out/stream_gen.tcl" -args "$sys" "$traj" "$frames" \
        </dev/null >/dev/null
fi

cat > "$out/stream_bench.tcl" <<'TCL'
lassign $argv sys traj dir w h
proc cpu {} {
    set f [open /proc/self/stat]; set s [read $f]; close $f
    set t [lrange [string range $s [string last ")" $s] end] 0 end]
    return [expr {([lindex $t 12] + [lindex $t 13]) / 100.0}]
}
mol new $sys waitfor all
animate delete all
mol addfile $traj waitfor all
set n [molinfo top get numframes]
set t0 [clock milliseconds]; set c0 [cpu]
movie make -basename $dir/f -type trajectory -size $w $h -renderer TachyonInternal -progress off
set t1 [clock milliseconds]; set c1 [cpu]
set m [dict create {*}[::molscope::memory top]]
puts [format "RESULT frames %d wall_ms_per_frame %.1f cpu_ms_per_frame %.1f peak_mb %.0f frames_mb %.1f" \
    $n [expr {($t1 - $t0) / double($n)}] [expr {1000.0 * ($c1 - $c0) / $n}] \
    [expr {[dict get $m peak] / 1e6}] [expr {[dict get $m frames] / 1e6}]]
quit
TCL

tsize=$(stat -c %s "$traj")
echo "bench_stream: $natoms atoms, $frames frames ($((tsize / 1000000)) MB), movie ${w}x$h, budget $budget"
printf '%-10s %-8s %8s %12s %12s %10s %10s\n' mode threads frames wall_ms/fr cpu_ms/fr peak_MB frames_MB
for mode in memory stream; do
    for th in default 1; do
        rm -rf "$out/stream_mv"; mkdir -p "$out/stream_mv"
        env=()
        [ "$th" = 1 ] && env+=(MOLSCOPE_THREADS=1)
        [ "$mode" = stream ] && env+=(MOLSCOPE_TRAJ_BUDGET=$budget)
        r=$(env "${env[@]}" "$molscope" -dispdev text -e "$out/stream_bench.tcl" \
            -args "$sys" "$traj" "$out/stream_mv" "$w" "$h" </dev/null | grep '^RESULT')
        set -- $r
        printf '%-10s %-8s %8s %12s %12s %10s %10s\n' "$mode" "$th" "$3" "$5" "$7" "$9" "${11}"
    done
done
rm -rf "$out/stream_mv"
