#!/usr/bin/env bash
# bench_load.sh: issue 2's benchmark. Loading a 1M-atom PDB (1tii replicated on a lattice;
# bond search and classification included) and streaming a 1M-atom x 100-frame DCD, beside
# MDAnalysis reading the same files in the same run; peak memory per atom.
#   scripts/bench/bench_load.sh [natoms] [frames]
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-1000000}; F=${2:-100}
out=bench-out; mkdir -p $out
pdb=$out/1tii_${N}.pdb; dcd=$out/1tii_${N}x${F}.dcd
PY=/usr/bin/python3
[ -f $pdb ] || $PY scripts/bench/replicate.py tests/data/1tii.pdb $N $pdb
export MOLSCOPE_TCLLIB=$PWD/tcl MOLSCOPE_PLUGINDIR=$PWD/plugins/.libs
MS=./src/molscope
have_mda=0; $PY -c 'import MDAnalysis' 2>/dev/null && have_mda=1

cat > $out/load.tcl <<'TCL'
lassign $argv file dcd
set t0 [clock microseconds]
set m [mol new $file waitfor all]
set t1 [clock microseconds]
puts "load [expr {($t1-$t0)/1e6}] [molinfo $m get numatoms]"
if {$dcd ne ""} {
    set t0 [clock microseconds]
    mol addfile $dcd waitfor all $m
    set t1 [clock microseconds]
    puts "dcd [expr {($t1-$t0)/1e6}] [molinfo $m get numframes] [file size $dcd]"
}
quit
TCL

best() { sort -g | head -1; }
echo "== molscope: load $pdb"
loads=""
for i in 1 2 3; do loads+="$($MS -dispdev text -e $out/load.tcl -args $pdb "" </dev/null | awk '/^load/{print $2}')"$'\n'; done
ms_load=$(printf '%s' "$loads" | best)
rss=$( { /usr/bin/time -f "%M" $MS -dispdev text -e $out/load.tcl -args $pdb "" </dev/null >/dev/null; } 2>&1 | tail -1)
base=$( { echo quit | /usr/bin/time -f "%M" $MS -dispdev text >/dev/null; } 2>&1 | tail -1)
natoms=$(grep -c '^ATOM\|^HETATM' $pdb)
bpa=$(awk -v r=$rss -v b=$base -v n=$natoms 'BEGIN{printf "%.1f", (r-b)*1024/n}')
echo "   best of 3: $ms_load s; peak RSS $rss KB (baseline $base KB): $bpa bytes/atom"

mda_load=n/a
if [ $have_mda = 1 ]; then
    mda_load=$($PY - $pdb <<'PY' 2>/dev/null | tail -1
import sys, time, warnings
warnings.filterwarnings("ignore")
import MDAnalysis as mda
t = time.time(); u = mda.Universe(sys.argv[1]); print("%.3f" % (time.time() - t))
PY
)
    echo "== MDAnalysis: parse $pdb: $mda_load s (no bonds guessed)"
fi

ms_dcd=n/a; mda_dcd=n/a; gbs=n/a
if [ -f plugins/.libs/dcd.so ] && [ $have_mda = 1 ]; then
    if [ ! -f $dcd ]; then
        echo "== writing $dcd with MDAnalysis"
        $PY - $pdb $dcd $F <<'PY' 2>/dev/null
import sys, warnings
warnings.filterwarnings("ignore")
import numpy as np, MDAnalysis as mda
u = mda.Universe(sys.argv[1]); x0 = u.atoms.positions.copy(); rng = np.random.default_rng(1)
with mda.Writer(sys.argv[2], n_atoms=len(u.atoms)) as w:
    for f in range(int(sys.argv[3])):
        u.atoms.positions = x0 + rng.normal(0, 0.3, x0.shape).astype(np.float32)
        w.write(u.atoms)
PY
    fi
    cat $dcd > /dev/null   # into the page cache
    runs=""
    for i in 1 2 3; do runs+="$($MS -dispdev text -e $out/load.tcl -args $pdb $dcd </dev/null | awk '/^dcd/{print $2}')"$'\n'; done
    ms_dcd=$(printf '%s' "$runs" | best)
    gbs=$(awk -v t=$ms_dcd -v s=$(stat -c %s $dcd) 'BEGIN{printf "%.2f", s/t/1e9}')
    mda_dcd=$($PY - $pdb $dcd <<'PY' 2>/dev/null | tail -1
import sys, time, warnings
warnings.filterwarnings("ignore")
import MDAnalysis as mda
u = mda.Universe(sys.argv[1], sys.argv[2])
t = time.time()
for ts in u.trajectory: pass
print("%.3f" % (time.time() - t))
PY
)
    echo "== DCD $F frames: molscope $ms_dcd s ($gbs GB/s), MDAnalysis $mda_dcd s"
fi
echo
printf '| %-38s | %10s | %10s | %7s |\n' "benchmark ($natoms atoms)" molscope MDAnalysis ratio
printf '| %-38s | %10s | %10s | %7s |\n' "PDB load (bonds+classification)" "$ms_load s" "$mda_load s" \
    "$(awk -v a=$ms_load -v b=$mda_load 'BEGIN{if (b+0>0) printf "%.1fx", b/a; else print "-"}')"
printf '| %-38s | %10s | %10s | %7s |\n' "DCD stream ($F frames)" "$ms_dcd s" "$mda_dcd s" \
    "$(awk -v a=$ms_dcd -v b=$mda_dcd 'BEGIN{if (b+0>0 && a+0>0) printf "%.1fx", b/a; else print "-"}')"
printf '| %-38s | %10s | %10s | %7s |\n' "DCD throughput" "$gbs GB/s" "" ""
printf '| %-38s | %10s | %10s | %7s |\n' "peak memory, bytes/atom" "$bpa" "" ""
