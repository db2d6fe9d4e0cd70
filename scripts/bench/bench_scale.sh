#!/usr/bin/env bash
# bench_scale.sh: issue 23's scale benchmark. An N-atom system (1tii replicated on a lattice
# by replicate.py; bonds by distance, residues, one segment a copy) is written once as a js
# file by molscope itself, then one molscope process (bench_scale.tcl) loads it, makes a
# QuickSurf of everything at 2 A coloured by chain, a NewCartoon of one copy and a 1920x1080
# TachyonInternal render with shadows and ambient occlusion. Printed: per stage the wall and
# CPU time and the peak resident memory (VmHWM) after it, and the bytes per atom of every
# structure (::molscope::memory). The render traces PASSES passes (default 1: one camera
# sample a pixel with its shadow and 12 occlusion rays; the memory does not depend on it).
#   scripts/bench/bench_scale.sh [natoms]          (default 1,000,000)
# MOLSCOPE=path runs another build's binary (its log and image tagged with TAG).
# Above 4M atoms run it under a memory cap (prlimit --as=...) on a shared machine.
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-1000000}
out=bench-out; mkdir -p $out
pdb=$out/1tii_${N}.pdb; js=$out/1tii_${N}.js
export MOLSCOPE_TCLLIB=$PWD/tcl MOLSCOPE_PLUGINDIR=$PWD/plugins/.libs
MS=${MOLSCOPE:-./src/molscope}     # MOLSCOPE=another/build/src/molscope: that build's figures

if [ ! -f $js ]; then
    [ -f $pdb ] || /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb $N $pdb
    printf '%s\n' 'lassign $argv in out' 'animate write js $out [mol new $in waitfor all]' quit \
        > $out/scale_write.tcl
    $MS -dispdev text -e $out/scale_write.tcl -args $pdb $js </dev/null >/dev/null
    rm -f $pdb
fi

log=$out/scale_${N}${TAG:-}.log
echo "== molscope scale: $js ($(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg))"
MOLSCOPE_RT_PASSES=${PASSES:-1} /usr/bin/time -f "TOTAL %e %U %S %M" \
    $MS -dispdev text -e scripts/bench/bench_scale.tcl -args $js $out/scale_${N}${TAG:-}.png \
    </dev/null >$log 2>&1 || { cat $log; exit 1; }
awk '
/^ATOMS/ {n = $2}
/^STAGE/ {printf "RESULT scale: %-10s %7.2f s wall %7.2f s cpu (%.2f user, %.2f system)   VmHWM %6.0f MB (%4.0f B/atom)\n", $2, $3, $4, $7, $8, $5/1e6, $5/n}
/^MEM/ && $2 != "rss" && $2 != "peak" {printf "RESULT scale:   %-13s %8.1f MB %7.1f B/atom\n", $2, $3/1e6, $3/n; sum += $3}
/^TOTAL/ {printf "RESULT scale: %d atoms: %.1f s wall, %.1f s cpu, peak %.0f MB = %.0f B/atom; 64M at this rate: %.1f GB\n", n, $2, $3+$4, $5*1024/1e6, $5*1024/n, $5*1024/n*64e6/1e9}
' $log
