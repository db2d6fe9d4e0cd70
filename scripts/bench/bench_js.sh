#!/usr/bin/env bash
# bench_js.sh: issue 20's js benchmark. A 16M-atom structure (1tii replicated on a lattice)
# is loaded from its PDB, written as a js file by molscope itself (structure, bonds, one
# frame), and loaded back from the js file, which is in the page cache; the page cache's own
# bandwidth on that file (dd to /dev/null) is the ceiling. Wall time of the load inside
# molscope (best of 3 for js), and the process's CPU time on all threads and on one
# (MOLSCOPE_THREADS=1).
#   scripts/bench/bench_js.sh [natoms]
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-16000000}
out=bench-out; mkdir -p $out
pdb=$out/1tii_${N}.pdb; js=$out/1tii_${N}.js
[ -f $pdb ] || /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb $N $pdb
export MOLSCOPE_TCLLIB=$PWD/tcl MOLSCOPE_PLUGINDIR=${PLUGINDIR:-$PWD/plugins/.libs}
MS=${MOLSCOPE:-./src/molscope}     # MOLSCOPE=other/molscope PLUGINDIR=its/plugins: another build

cat > $out/js.tcl <<'TCL'
lassign $argv file write
set t0 [clock microseconds]
set m [mol new $file waitfor all]
set t1 [clock microseconds]
puts "load [expr {($t1-$t0)/1e6}] [molinfo $m get numatoms] [llength [join [[atomselect $m "index < 1000"] getbonds]]]"
if {$write ne ""} {
    set t0 [clock microseconds]
    animate write js $write $m
    puts "write [expr {([clock microseconds]-$t0)/1e6}] [file size $write]"
}
quit
TCL

# run <threads> <file> [write]: "seconds-in-molscope cpu-seconds atoms write-seconds
# peak-resident-kB" of one load
run() {
    local th=$1; shift
    local log; log=$(mktemp)
    MOLSCOPE_THREADS=$th /usr/bin/time -f "cpu %U %S %M" $MS -dispdev text -e $out/js.tcl -args "$@" \
        </dev/null >$log 2>&1
    awk '/^load/{t=$2; n=$3} /^write/{w=$2} /^cpu/{c=$2+$3; k=$4} END{print t, c, n, (w == "" ? 0 : w), k}' $log
    rm -f $log
}
best() { sort -g | head -1; }

echo "== molscope: load $pdb and write $js"
read -r pdb_s pdb_cpu natoms write_s _ <<<"$(run 0 $pdb $js)"
read -r pdb1_s pdb1_cpu _ _ pdb_kb <<<"$(run 1 $pdb)"
echo "   PDB load $pdb_s s (cpu $pdb_cpu s); one thread $pdb1_s s (cpu $pdb1_cpu s); js written in $write_s s"

size=$(stat -c %s $js)
cat $js > /dev/null
cache=$(for i in 1 2 3; do
    s=$(date +%s.%N); dd if=$js of=/dev/null bs=16M status=none; e=$(date +%s.%N)
    awk -v s=$s -v e=$e 'BEGIN{print e - s}'
done | best)
echo "   page cache: $size bytes in $cache s"

js_runs=$(for i in 1 2 3; do run 0 $js; done)
js_s=$(printf '%s\n' "$js_runs" | awk '{print $1}' | best)
js_cpu=$(printf '%s\n' "$js_runs" | awk '{print $2}' | best)
js1_runs=$(for i in 1 2 3; do run 1 $js; done)
js1_s=$(printf '%s\n' "$js1_runs" | awk '{print $1}' | best)
js1_cpu=$(printf '%s\n' "$js1_runs" | awk '{print $2}' | best)
js_kb=$(printf '%s\n' "$js1_runs" | awk '{print $5}' | best)
echo "   js load best of 3: $js_s s (cpu $js_cpu s); one thread $js1_s s (cpu $js1_cpu s)"

awk -v n=$natoms -v sz=$size -v c=$cache -v j=$js_s -v j1=$js1_s -v p=$pdb_s -v p1=$pdb1_s \
    -v jc=$js_cpu -v pc=$pdb_cpu -v j1c=$js1_cpu -v p1c=$pdb1_cpu -v jk=$js_kb -v pk=$pdb_kb 'BEGIN{
    printf "RESULT js: %d atoms, %.0f MB js file\n", n, sz/1e6
    printf "RESULT js: page cache %.2f GB/s (%.2f s for the file)\n", sz/c/1e9, c
    printf "RESULT js: js load %.2f s wall (%.2f s cpu), one thread %.2f s: %.2f GB/s, %.0f%% of the page cache\n", j, jc, j1, sz/j/1e9, 100*c/j
    printf "RESULT js: PDB load %.2f s wall (%.2f s cpu), one thread %.2f s: js is %.1fx faster\n", p, pc, p1, p/j
    printf "RESULT js: one thread, cpu: js %.2f s, PDB %.2f s: js is %.1fx faster\n", j1c, p1c, p1c/j1c
    printf "RESULT js: peak resident after the load (one thread): js %.0f MB (%.0f B/atom), PDB %.0f MB (%.0f B/atom)\n", jk*1024/1e6, jk*1024/n, pk*1024/1e6, pk*1024/n
}'
