#!/usr/bin/env bash
# bench_netcdf.sh: reading an AMBER NetCDF trajectory, molscope beside MDAnalysis on the
# same file in the same run. netCDF4 (python3-netcdf4) writes NATOMS (default 1,000,000)
# atoms x NFRAMES (default 100) frames in the AMBER convention (64-bit offset format, float
# coordinates, a cell and a time per frame) into bench-out/ (1.2 GB; made here, never
# committed). molscope reads every frame into memory (`mol new atoms N; mol addfile x.nc
# waitfor all`, timed inside the program, the molecule creation excluded; CPU time from
# /proc/self/stat), once with the default threads and once with MOLSCOPE_THREADS=1;
# MDAnalysis 2.4.2 iterates the trajectory (its NCDF reader: every frame's positions, cell
# and time into its Timestep). The file is read once before the clocks start so both read
# it from the page cache. Prints wall and CPU seconds of each (best of REPEAT, default 3)
# and the ratios.
#
# usage: scripts/bench/bench_netcdf.sh [builddir]   (NATOMS, NFRAMES, REPEAT override)
set -eu
. "$(dirname "$0")/lib.sh" "$@"
nframes=${NFRAMES:-100}
repeat=${REPEAT:-3}
nc="$out/amber_${natoms}_${nframes}.nc"
if ! grep -q "define MS_HAVE_NETCDF 1" "$build/config.h"; then
    echo "bench_netcdf: molscope was built without libnetcdf: skipped"
    exit 0
fi
if [ ! -f "$nc" ]; then
    /usr/bin/python3 - "$nc" "$natoms" "$nframes" <<'PY'
import sys
import numpy as np
import netCDF4
path, n, nf = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
ds = netCDF4.Dataset(path + ".tmp", "w", format="NETCDF3_64BIT_OFFSET")
ds.Conventions, ds.ConventionVersion, ds.program = "AMBER", "1.0", "bench_netcdf.sh"
for name, size in (("frame", None), ("spatial", 3), ("atom", n), ("cell_spatial", 3),
                   ("cell_angular", 3), ("label", 5)):
    ds.createDimension(name, size)
t = ds.createVariable("time", "f4", ("frame",))
t.units = "picosecond"
c = ds.createVariable("coordinates", "f4", ("frame", "atom", "spatial"))
c.units = "angstrom"
cl = ds.createVariable("cell_lengths", "f8", ("frame", "cell_spatial"))
cl.units = "angstrom"
ca = ds.createVariable("cell_angles", "f8", ("frame", "cell_angular"))
ca.units = "degree"
rng = np.random.default_rng(1)
xyz = rng.uniform(0, 220, (n, 3)).astype(np.float32)
for k in range(nf):
    c[k] = xyz + 0.01 * k
    cl[k] = [220.0 + 0.01 * k] * 3
    ca[k] = [90.0] * 3
    t[k] = 2.0 * k
ds.close()
import os
os.rename(path + ".tmp", path)
PY
fi
size=$(stat -c %s "$nc")
echo "file: $nc ($natoms atoms, $nframes frames, $((size / 1048576)) MB)"
cat "$nc" > /dev/null

cat > "$out/bench_netcdf.tcl" <<TCL
proc cpu {} {
    set f [open /proc/self/stat]
    set s [read \$f]
    close \$f
    set s [string range \$s [expr {[string last ")" \$s] + 2}] end]
    expr {([lindex \$s 11] + [lindex \$s 12]) / 100.0}
}
set m [mol new atoms $natoms]
set best 1e9
set bestcpu 1e9
for {set r 0} {\$r < $repeat} {incr r} {
    animate delete all \$m
    set c0 [cpu]
    set t0 [clock microseconds]
    mol addfile $nc type netcdf waitfor all \$m
    set t [expr {([clock microseconds] - \$t0) / 1e6}]
    set c [expr {[cpu] - \$c0}]
    if {\$t < \$best} { set best \$t }
    if {\$c < \$bestcpu} { set bestcpu \$c }
}
puts "molscope [molinfo \$m get numframes] \$best \$bestcpu"
TCL
run_ms() {
    env "$@" MOLSCOPE_PLUGINDIR="$build/plugins/.libs" MOLSCOPE_TCLLIB="$src/tcl" \
        "$build/src/molscope" -dispdev text -e "$out/bench_netcdf.tcl" < /dev/null | grep '^molscope'
}
ms=$(run_ms)
ms1=$(run_ms MOLSCOPE_THREADS=1)
mda=$(/usr/bin/python3 - "$nc" "$natoms" "$repeat" <<'PY'
import sys, time, warnings
warnings.simplefilter("ignore")
import MDAnalysis as mda
u = mda.Universe.empty(int(sys.argv[2]), trajectory=False)
u.load_new(sys.argv[1], format="NCDF")
import numpy as np
best = bestcpu = kbest = kcpu = 1e9
for r in range(int(sys.argv[3])):
    t0, c0 = time.perf_counter(), time.process_time()
    for ts in u.trajectory:
        pass
    best = min(best, time.perf_counter() - t0)
    bestcpu = min(bestcpu, time.process_time() - c0)
    # The same work as molscope's: every frame kept in memory.
    t0, c0 = time.perf_counter(), time.process_time()
    keep = np.empty((len(u.trajectory), u.atoms.n_atoms, 3), dtype=np.float32)
    for k, ts in enumerate(u.trajectory):
        keep[k] = ts.positions
    kbest = min(kbest, time.perf_counter() - t0)
    kcpu = min(kcpu, time.process_time() - c0)
    del keep
print("mdanalysis", len(u.trajectory), best, bestcpu, kbest, kcpu)
PY
)
read -r _ f1 t1 c1 <<< "$ms"
read -r _ f1b t1b c1b <<< "$ms1"
read -r _ f2 t2 c2 t3 c3 <<< "$mda"
echo "molscope, every frame kept:               $f1 frames in $t1 s wall, $c1 s CPU"
echo "molscope (MOLSCOPE_THREADS=1), kept:      $f1b frames in $t1b s wall, $c1b s CPU"
echo "MDAnalysis, iterating (one Timestep):     $f2 frames in $t2 s wall, $c2 s CPU"
echo "MDAnalysis, every frame kept (numpy):     $f2 frames in $t3 s wall, $c3 s CPU"
/usr/bin/python3 -c "import sys; w, c, w2, c2, w3, c3 = map(float, sys.argv[1:]); \
print('MDAnalysis / molscope (one thread): kept wall %.2fx CPU %.2fx; iterating wall %.2fx CPU %.2fx' % (w3 / w, c3 / c, w2 / w, c2 / c))" \
    "$t1b" "$c1b" "$t2" "$c2" "$t3" "$c3"
