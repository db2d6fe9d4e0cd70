#!/usr/bin/env bash
# bench_pbc.sh: pbctools' `pbc wrap` and `pbc unwrap` on 1M atoms x 100 frames, molscope
# beside MDAnalysis in the same run. 1tii.pdb is replicated to ~1M atoms (replicate.py);
# both programs build the same trajectory in memory from it: frame f is the structure moved
# by f (1.3, -0.7, 0.4) A, every frame in the monoclinic cell (0.8 x the structure's extent,
# angles 80 85 90; gamma 90 because MDAnalysis 2.4's wrap is not the exact parallelepiped
# otherwise). Timed: wrap of every frame (atoms into the cell), then unwrap of the wrapped
# frames (every atom to the image nearest its previous position). MDAnalysis on a
# MemoryReader trajectory, each way a user may write it, every variant from the same
# starting coordinates: wrap by AtomGroup.wrap per frame (what its transformations.wrap
# does) and by its C routine apply_PBC straight on each frame's coordinate array (no
# AtomGroup copies); unwrap (2.4 has no NoJump) by the loop with minimize_vectors against
# the previous frame, and vectorised with numpy: fractional offsets by its C transform_RtoS,
# rounded by numpy, back by transform_StoR, in place. molscope also times
# `pbc join residue -all`. Wall and CPU time; molscope with all cores and with
# MOLSCOPE_THREADS=1 (MDAnalysis runs on one). A checksum of the last frame shows every
# variant computed the same coordinates.
#
# usage: scripts/bench/bench_pbc.sh [builddir]   (NATOMS, NFRAMES override)
set -eu
. "$(dirname "$0")/lib.sh" "$@"
nframes=${NFRAMES:-100}
pdb="$out/pbc_${natoms}.pdb"
bench_replicate "$pdb"

cat > "$out/bench_pbc.tcl" <<TCL
proc cpu {} {
    set f [open /proc/self/stat]; set s [read \$f]; close \$f
    set w [split [string range \$s [expr {[string last ")" \$s] + 2}] end]]
    expr {([lindex \$w 11] + [lindex \$w 12]) / 100.0}
}
proc timed {name script} {
    set c [cpu]; set t [clock microseconds]
    uplevel 1 \$script
    puts "molscope \$name [expr {([clock microseconds] - \$t) / 1e6}] [expr {[cpu] - \$c}] [checksum]"
}
proc checksum {} {
    set s [atomselect top all frame last]
    set sum 0.0
    foreach v [join [\$s get {x y z}]] { set sum [expr {\$sum + abs(\$v)}] }
    \$s delete
    return \$sum
}
set m [mol new $pdb waitfor all]
set all [atomselect \$m all]
lassign [measure minmax \$all] lo hi
set e [vecscale 0.8 [vecsub \$hi \$lo]]
for {set f 1} {\$f < $nframes} {incr f} { animate dup \$m }
pbc set [list {*}\$e 80 85 90] -all
for {set f 1} {\$f < $nframes} {incr f} {
    \$all frame \$f
    \$all moveby [vecscale \$f {1.3 -0.7 0.4}]
}
puts "atoms [molinfo \$m get numatoms] frames [molinfo \$m get numframes]"
timed wrap { pbc wrap -all }
timed unwrap { pbc unwrap -all }
timed join { pbc join residue -all }
quit
TCL
run_ms() {
    env "$@" MOLSCOPE_PLUGINDIR="$build/plugins/.libs" MOLSCOPE_TCLLIB="$src/tcl" \
        "$build/src/molscope" -dispdev text -e "$out/bench_pbc.tcl" < /dev/null | grep '^molscope\|^atoms'
}
echo "== molscope, all cores ($(nproc))"; run_ms MOLSCOPE_THREADS=0
echo "== molscope, MOLSCOPE_THREADS=1"; run_ms MOLSCOPE_THREADS=1
echo "== MDAnalysis $(/usr/bin/python3 -c 'import MDAnalysis; print(MDAnalysis.__version__)' 2>/dev/null)"
OMP_NUM_THREADS=1 /usr/bin/python3 - "$pdb" "$nframes" <<'PY'
import sys, time, warnings
warnings.simplefilter("ignore")
import numpy as np
import MDAnalysis as mda
from MDAnalysis.coordinates.memory import MemoryReader
from MDAnalysis.lib.distances import apply_PBC, minimize_vectors, transform_RtoS, transform_StoR

u = mda.Universe(sys.argv[1])
n = int(sys.argv[2])
p0 = u.atoms.positions.astype(np.float32)
e = 0.8 * (p0.max(axis=0) - p0.min(axis=0))
dims = np.array([e[0], e[1], e[2], 80, 85, 90], dtype=np.float32)
step = np.array([1.3, -0.7, 0.4], dtype=np.float32)
coords = np.empty((n, len(p0), 3), dtype=np.float32)
for f in range(n):
    coords[f] = p0 + f * step
u.load_new(coords, format=MemoryReader, dimensions=np.tile(dims, (n, 1)))
del coords
ag = u.atoms
ca = u.trajectory.coordinate_array    # (frames, atoms, 3), what every frame's positions view
da = u.trajectory.dimensions_array
start = ca.copy()


def timed(name, fn):
    c, t = time.process_time(), time.perf_counter()
    fn()
    wall, cpu = time.perf_counter() - t, time.process_time() - c
    u.trajectory[-1]
    print("mdanalysis %s %.3f %.3f %.1f" % (name, wall, cpu, float(np.abs(ag.positions.astype(np.float64)).sum())), flush=True)


def wrap_atomgroup():
    for ts in u.trajectory:
        ag.wrap(compound="atoms")


def wrap_apply_pbc():
    for f in range(n):
        ca[f] = apply_PBC(ca[f], da[f])


def unwrap_minimize_vectors():
    prev = None
    for ts in u.trajectory:
        if prev is not None:
            ag.positions = prev + minimize_vectors(ag.positions - prev, ts.dimensions)
        prev = ag.positions.copy()


def unwrap_numpy():
    for f in range(1, n):
        s = transform_RtoS(ca[f] - ca[f - 1], da[f])
        np.rint(s, out=s)
        ca[f] -= transform_StoR(s, da[f])


timed("wrap(AtomGroup.wrap)", wrap_atomgroup)
ca[...] = start
timed("wrap(apply_PBC)", wrap_apply_pbc)
start[...] = ca
timed("unwrap(minimize_vectors)", unwrap_minimize_vectors)
ca[...] = start
timed("unwrap(numpy)", unwrap_numpy)
PY
