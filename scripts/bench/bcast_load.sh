#!/usr/bin/env bash
# bcast_load.sh: load time of one structure on N MPI ranks, every rank reading the file
# itself (MOLSCOPE_NOBCAST=1) against rank 0 reading it and broadcasting the molecule.
#
#   scripts/bench/bcast_load.sh [file.pdb] [ranks...] [-r repeats]
#
# Without a file it builds bench-out/x.pdb, a 1M-atom PDB replicated from tests/data/1tii.pdb.
# Each run starts the clock after a barrier and stops it when every rank has the molecule
# (a second barrier); it prints the best of the repeats, the CPU time all ranks spent on
# the load (summed; it varies less than wall time on a shared machine), rank 0's peak
# memory and the largest peak memory of any rank.
set -eu
srcdir=$(cd "$(dirname "$0")/../.." && pwd)
molscope=${MOLSCOPE:-$srcdir/src/molscope}
repeats=3
args=()
while [ $# -gt 0 ]; do
    case $1 in -r) repeats=$2; shift 2;; *) args+=("$1"); shift;; esac
done
file=${args[0]:-}
ranks=("${args[@]:1}")
[ ${#ranks[@]} -gt 0 ] || ranks=(1 2 4)
if [ -z "$file" ]; then
    mkdir -p "$srcdir/bench-out"
    file=$srcdir/bench-out/x.pdb
    [ -f "$file" ] || /usr/bin/python3 "$srcdir/scripts/bench/replicate.py" \
        "$srcdir/tests/data/1tii.pdb" 1000000 "$file"
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export MOLSCOPE_TCLLIB=${MOLSCOPE_TCLLIB:-$srcdir/tcl}
export CLK_TCK=$(getconf CLK_TCK)
script=$(mktemp /tmp/bcast_load.XXXXXX.tcl)
trap 'rm -f "$script"' EXIT
cat > "$script" <<'TCL'
proc maxof {a b} { expr {max($a, $b)} }
proc sum {a b} { expr {$a + $b} }
# CPU seconds of this process (utime + stime from /proc, in clock ticks)
proc cpu {} {
    set f [open /proc/self/stat]; set s [read $f]; close $f
    set fields [split [string range $s [string last ) $s]+2 end]]
    expr {([lindex $fields 11] + [lindex $fields 12]) / double($::env(CLK_TCK))}
}
set bcast [expr {[info exists env(MOLSCOPE_NOBCAST)] ? "off" : "on"}]
parallel barrier
set c0 [cpu]
set t0 [clock microseconds]
mol new [lindex $argv 0] waitfor all bcast $bcast
parallel barrier
set t [expr {([clock microseconds] - $t0) / 1e6}]
set cputotal [parallel allreduce sum [expr {[cpu] - $c0}]]
set rss 0
if {![catch {open /proc/self/status} f]} {
    foreach line [split [read $f] \n] { if {[regexp {^VmHWM:\s+(\d+)} $line -> rss]} break }
    close $f
}
set maxrss [parallel allreduce maxof $rss]
if {[parallel noderank] == 0} {
    puts [format "RESULT %.3f %d %d %d %.2f" $t [molinfo top get numatoms] $rss $maxrss $cputotal]
}
quit
TCL
size=$(du -m "$file" | cut -f1)
natoms=
printf '%-6s %-22s %10s %12s %14s %14s\n' ranks mode "load (s)" "CPU (s)" "rank 0 (MiB)" \
    "max rank (MiB)"
for n in "${ranks[@]}"; do
    for mode in read bcast; do
        best=
        for ((k = 0; k < repeats; k++)); do
            env=()
            [ $mode = read ] && env=(-x MOLSCOPE_NOBCAST=1)
            line=$(mpirun -np "$n" "${env[@]}" "$molscope" -dispdev text -e "$script" \
                   -args "$file" </dev/null 2>/dev/null | tr -d '\r' | grep '^RESULT')
            set -- $line
            natoms=$3
            if [ -z "$best" ] || awk -v a="$2" -v b="${best%% *}" 'BEGIN{exit !(a < b)}'; then
                best="$2 $4 $5 $6"
            fi
        done
        set -- $best
        label=$([ $mode = read ] && echo "every rank reads" || echo "rank 0 reads, bcast")
        printf '%-6s %-22s %10s %12s %14d %14d\n' "$n" "$label" "$1" "$4" $(($2 / 1024)) \
            $(($3 / 1024))
    done
done
echo "($natoms atoms, ${size} MB PDB, best of $repeats; $(nproc) cores; $(mpirun --version | head -1))"
