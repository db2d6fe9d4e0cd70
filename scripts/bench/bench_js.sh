#!/usr/bin/env bash
# bench_js.sh: the js benchmark of issues 20 and 23. An N-atom structure (1tii replicated on a
# lattice, default 16M atoms) is loaded from its PDB, written as a js file by molscope itself
# (structure, bonds, one frame), and loaded back from the js file, which is in the page cache;
# the page cache's own bandwidth on that file (dd to /dev/null) is the ceiling. Printed: the
# wall time of the load inside molscope (best of REPS, default 3), the CPU time of the load
# itself (`mol new`, measured inside the process: every thread's run time from
# /proc/self/task/*/schedstat) and of the whole process (/usr/bin/time: start-up and exit
# included), on all threads and on one (MOLSCOPE_THREADS=1), and the peak resident memory.
#   scripts/bench/bench_js.sh [natoms]
# MOLSCOPE=other/molscope PLUGINDIR=its/plugins: another build's figures. JS_ONLY=1: the js
# load alone (its file is kept in bench-out; the PDB of 64M atoms is 5 GB and is not).
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-16000000}
REPS=${REPS:-3}
out=bench-out; mkdir -p $out
pdb=$out/1tii_${N}.pdb; js=$out/1tii_${N}.js
export MOLSCOPE_TCLLIB=$PWD/tcl MOLSCOPE_PLUGINDIR=${PLUGINDIR:-$PWD/plugins/.libs}
MS=${MOLSCOPE:-./src/molscope}     # MOLSCOPE=other/molscope PLUGINDIR=its/plugins: another build
[ -n "${JS_ONLY:-}" ] || [ -f $pdb ] ||
    /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb $N $pdb

cat > $out/js.tcl <<'TCL'
lassign $argv file write
# Run time of every thread of this process so far, in ns (schedstat's first field).
proc cpu_ns {} {
    set t 0
    foreach p [glob -nocomplain /proc/self/task/*/schedstat] {
        set f [open $p]
        set t [expr {$t + [lindex [read $f] 0]}]
        close $f
    }
    return $t
}
set c0 [cpu_ns]
set t0 [clock microseconds]
set m [mol new $file waitfor all]
set t1 [clock microseconds]
set c1 [cpu_ns]
puts "load [expr {($t1-$t0)/1e6}] [molinfo $m get numatoms] [llength [join [[atomselect $m "index < 1000"] getbonds]]] [expr {($c1-$c0)/1e9}]"
if {$write ne ""} {
    set t0 [clock microseconds]
    animate write js $write $m
    puts "write [expr {([clock microseconds]-$t0)/1e6}] [file size $write]"
}
quit
TCL

# run <threads> <file> [write]: "seconds-in-molscope process-cpu-seconds atoms write-seconds
# peak-resident-kB load-cpu-seconds" of one load
run() {
    local th=$1; shift
    local log; log=$(mktemp)
    MOLSCOPE_THREADS=$th /usr/bin/time -f "cpu %U %S %M" $MS -dispdev text -e $out/js.tcl -args "$@" \
        </dev/null >$log 2>&1
    awk '/^load/{t=$2; n=$3; lc=$5} /^write/{w=$2} /^cpu/{c=$2+$3; k=$4}
         END{print t, c, n, (w == "" ? 0 : w), k, lc}' $log
    rm -f $log
}
best() { sort -g | head -1; }
# bestcol <column> <runs>: the smallest value of that column
bestcol() { printf '%s\n' "$2" | awk -v c=$1 '{print $c}' | best; }

if [ -z "${JS_ONLY:-}" ]; then
    echo "== molscope: load $pdb and write $js"
    read -r pdb_s pdb_cpu natoms write_s _ _ <<<"$(run 0 $pdb $js)"
    pdb1_runs=$(for i in $(seq $REPS); do run 1 $pdb; done)
    pdb1_s=$(bestcol 1 "$pdb1_runs"); pdb1_cpu=$(bestcol 2 "$pdb1_runs")
    pdb_kb=$(bestcol 5 "$pdb1_runs"); pdb1_load=$(bestcol 6 "$pdb1_runs")
    echo "   PDB load $pdb_s s (cpu $pdb_cpu s); one thread $pdb1_s s (cpu $pdb1_cpu s, the load $pdb1_load s); js written in $write_s s"
fi

size=$(stat -L -c %s $js)
cat $js > /dev/null
cache=$(for i in 1 2 3; do
    s=$(date +%s.%N); dd if=$js of=/dev/null bs=16M status=none; e=$(date +%s.%N)
    awk -v s=$s -v e=$e 'BEGIN{print e - s}'
done | best)
echo "   page cache: $size bytes in $cache s"

js_runs=$(for i in $(seq $REPS); do run 0 $js; done)
js_s=$(bestcol 1 "$js_runs"); js_cpu=$(bestcol 2 "$js_runs")
js1_runs=$(for i in $(seq $REPS); do run 1 $js; done)
js1_s=$(bestcol 1 "$js1_runs"); js1_cpu=$(bestcol 2 "$js1_runs")
js_kb=$(bestcol 5 "$js1_runs"); js1_load=$(bestcol 6 "$js1_runs")
natoms=$(bestcol 3 "$js1_runs")
echo "   js load best of $REPS: $js_s s (cpu $js_cpu s); one thread $js1_s s (cpu $js1_cpu s, the load $js1_load s)"

awk -v n=$natoms -v sz=$size -v c=$cache -v j=$js_s -v j1=$js1_s -v jc=$js_cpu -v j1c=$js1_cpu \
    -v j1l=$js1_load -v jk=$js_kb 'BEGIN{
    printf "RESULT js: %d atoms, %.0f MB js file\n", n, sz/1e6
    printf "RESULT js: page cache %.2f GB/s (%.2f s for the file)\n", sz/c/1e9, c
    printf "RESULT js: js load %.2f s wall (%.2f s cpu), one thread %.2f s: %.2f GB/s, %.0f%% of the page cache\n", j, jc, j1, sz/j/1e9, 100*c/j
    printf "RESULT js: one thread: js load %.3f s cpu (the process %.2f s), peak resident %.0f MB (%.0f B/atom)\n", j1l, j1c, jk*1024/1e6, jk*1024/n
}'
[ -n "${JS_ONLY:-}" ] && exit 0
awk -v j=$js_s -v p=$pdb_s -v j1c=$js1_cpu -v p1c=$pdb1_cpu -v j1l=$js1_load -v p1l=$pdb1_load \
    -v pk=$pdb_kb -v n=$natoms 'BEGIN{
    printf "RESULT js: PDB load %.2f s wall: js is %.1fx faster\n", p, p/j
    printf "RESULT js: one thread, cpu of the load: js %.3f s, PDB %.3f s: js is %.1fx faster\n", j1l, p1l, p1l/j1l
    printf "RESULT js: one thread, cpu of the process: js %.2f s, PDB %.2f s: js is %.1fx faster\n", j1c, p1c, p1c/j1c
    printf "RESULT js: peak resident after the PDB load (one thread): %.0f MB (%.0f B/atom)\n", pk*1024/1e6, pk*1024/n
}'
