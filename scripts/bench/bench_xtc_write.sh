#!/usr/bin/env bash
# bench_xtc_write.sh: XTC writing throughput, molscope beside MDAnalysis on the same frames
# in the same run. 1tii.pdb is replicated to ~1M atoms (replicate.py); MDAnalysis writes
# NFRAMES (default 10) frames of it, each moved by 0.1 A and jittered, as XTC into
# bench-out/. molscope loads them (`mol new x.pdb; mol addfile x.xtc`) and writes them again
# (`animate write xtc ... beg 1`, timed inside the program: encoding and writing to the page
# cache); MDAnalysis writes the same frames from memory (transfer_to_memory before the
# clock starts). Prints atoms per second of each and the ratio. Best of REPEAT (3) runs.
#
# usage: scripts/bench/bench_xtc_write.sh [builddir]   (NATOMS, NFRAMES, REPEAT override)
set -eu
. "$(dirname "$0")/lib.sh" "$@"
nframes=${NFRAMES:-10}
repeat=${REPEAT:-3}
pdb="$out/xtc_${natoms}.pdb"
xtc="$out/xtcw_${natoms}_${nframes}.xtc"
bench_replicate "$pdb"
if [ ! -f "$xtc" ]; then
    /usr/bin/python3 - "$pdb" "$xtc" "$nframes" <<'PY'
import sys, warnings
warnings.simplefilter("ignore")
import numpy as np
import MDAnalysis as mda
u = mda.Universe(sys.argv[1])
rng = np.random.default_rng(1)
base = u.atoms.positions.copy()
with mda.Writer(sys.argv[2], u.atoms.n_atoms) as w:
    for k in range(int(sys.argv[3])):
        u.atoms.positions = base + 0.1 * k + rng.normal(0, 0.05, base.shape).astype(np.float32)
        w.write(u.atoms)
PY
fi
cat > "$out/bench_xtc_write.tcl" <<TCL
set m [mol new $pdb]
mol addfile $xtc waitfor all \$m
set best 1e9
for {set r 0} {\$r < $repeat} {incr r} {
    set t0 [clock microseconds]
    animate write xtc $out/xtcw_ours.xtc beg 1 \$m
    set t [expr {([clock microseconds] - \$t0) / 1e6}]
    if {\$t < \$best} { set best \$t }
}
puts "molscope [expr {[molinfo \$m get numframes] - 1}] \$best [file size $out/xtcw_ours.xtc]"
TCL
ms=$(MOLSCOPE_PLUGINDIR="$build/plugins/.libs" MOLSCOPE_TCLLIB="$src/tcl" \
     "$build/src/molscope" -dispdev text -e "$out/bench_xtc_write.tcl" < /dev/null | grep '^molscope')
mda=$(/usr/bin/python3 - "$pdb" "$xtc" "$repeat" "$out/xtcw_mda.xtc" <<'PY'
import os, sys, time, warnings
warnings.simplefilter("ignore")
import MDAnalysis as mda
u = mda.Universe(sys.argv[1], sys.argv[2])
u.transfer_to_memory()
best = 1e9
for r in range(int(sys.argv[3])):
    t0 = time.perf_counter()
    with mda.Writer(sys.argv[4], u.atoms.n_atoms) as w:
        for ts in u.trajectory:
            w.write(u.atoms)
    best = min(best, time.perf_counter() - t0)
print("mdanalysis", len(u.trajectory), best, os.path.getsize(sys.argv[4]))
PY
)
read -r _ f1 t1 s1 <<< "$ms"
read -r _ f2 t2 s2 <<< "$mda"
n=$(grep -c '^ATOM\|^HETATM' "$pdb")
/usr/bin/python3 - "$n" "$f1" "$t1" "$s1" "$f2" "$t2" "$s2" <<'PY'
import sys
n = int(sys.argv[1])
f1, t1, s1, f2, t2, s2 = int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), \
    int(sys.argv[5]), float(sys.argv[6]), int(sys.argv[7])
a, b = n * f1 / t1, n * f2 / t2
print("atoms: %d" % n)
print("molscope:   %d frames in %.3f s: %.1f M atoms/s, %.0f ms a frame, %.2f bytes an atom"
      % (f1, t1, a / 1e6, 1e3 * t1 / f1, s1 / (n * f1)))
print("MDAnalysis: %d frames in %.3f s: %.1f M atoms/s, %.0f ms a frame, %.2f bytes an atom"
      % (f2, t2, b / 1e6, 1e3 * t2 / f2, s2 / (n * f2)))
print("ratio molscope / MDAnalysis: %.2f" % (a / b))
PY
