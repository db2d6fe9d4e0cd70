#!/usr/bin/env bash
# bench_xtc.sh: XTC decoding throughput, molscope beside MDAnalysis on the same file in the
# same run. 1tii.pdb is replicated to ~1M atoms (replicate.py); MDAnalysis writes NFRAMES
# (default 50) frames of it, each moved by 0.1 A, as XTC (precision 1000, GROMACS' default)
# into bench-out/. molscope reads every frame (`mol new atoms N; mol addfile x.xtc waitfor
# all`, timed inside the program, the molecule creation excluded); MDAnalysis iterates the
# trajectory (positions decoded and converted to Angstrom, the offsets index built before
# the clock starts). Prints atoms per second of each and the ratio. Best of REPEAT (3) runs.
#
# usage: scripts/bench/bench_xtc.sh [builddir]   (NATOMS, NFRAMES, REPEAT override)
set -eu
. "$(dirname "$0")/lib.sh" "$@"
nframes=${NFRAMES:-50}
repeat=${REPEAT:-3}
pdb="$out/xtc_${natoms}.pdb"
xtc="$out/xtc_${natoms}_${nframes}.xtc"
bench_replicate "$pdb"
if [ ! -f "$xtc" ]; then
    /usr/bin/python3 - "$pdb" "$xtc" "$nframes" <<'PY'
import sys, warnings
warnings.simplefilter("ignore")
import MDAnalysis as mda
u = mda.Universe(sys.argv[1])
with mda.Writer(sys.argv[2], u.atoms.n_atoms) as w:
    for k in range(int(sys.argv[3])):
        u.atoms.positions += 0.1
        w.write(u.atoms)
PY
fi
n=$(/usr/bin/python3 -c "import struct,sys; f=open(sys.argv[1],'rb'); print(struct.unpack('>ii', f.read(8))[1])" "$xtc")
size=$(stat -c %s "$xtc")
echo "file: $xtc ($n atoms, $nframes frames, $((size / 1048576)) MB)"

cat > "$out/bench_xtc.tcl" <<TCL
set m [mol new atoms $n]
set best 1e9
for {set r 0} {\$r < $repeat} {incr r} {
    animate delete all \$m
    set t0 [clock microseconds]
    mol addfile $xtc waitfor all \$m
    set t [expr {([clock microseconds] - \$t0) / 1e6}]
    if {\$t < \$best} { set best \$t }
}
puts "molscope [molinfo \$m get numframes] \$best"
TCL
ms=$(MOLSCOPE_PLUGINDIR="$build/plugins/.libs" MOLSCOPE_TCLLIB="$src/tcl" \
     "$build/src/molscope" -dispdev text -e "$out/bench_xtc.tcl" < /dev/null | grep '^molscope')
mda=$(/usr/bin/python3 - "$pdb" "$xtc" "$repeat" <<'PY'
import sys, time, warnings
warnings.simplefilter("ignore")
import MDAnalysis as mda
u = mda.Universe(sys.argv[1], sys.argv[2])
best = 1e9
for r in range(int(sys.argv[3])):
    t0 = time.perf_counter()
    for ts in u.trajectory:
        pass
    best = min(best, time.perf_counter() - t0)
print("mdanalysis", len(u.trajectory), best)
PY
)
read -r _ f1 t1 <<< "$ms"
read -r _ f2 t2 <<< "$mda"
/usr/bin/python3 - "$n" "$f1" "$t1" "$f2" "$t2" <<'PY'
import sys
n, f1, t1, f2, t2 = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
a, b = n * f1 / t1, n * f2 / t2
print("molscope:   %d frames in %.3f s: %.1f M atoms/s" % (f1, t1, a / 1e6))
print("MDAnalysis: %d frames in %.3f s: %.1f M atoms/s" % (f2, t2, b / 1e6))
print("ratio molscope / MDAnalysis: %.2f" % (a / b))
PY
