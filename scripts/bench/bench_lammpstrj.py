#!/usr/bin/python3
"""bench_lammpstrj.py: reading a LAMMPS text dump, molscope beside MDAnalysis on the same
file in the same run (run by bench_lammpstrj.sh). 1tii.pdb is replicated to ~1M atoms
(replicate.py); NFRAMES (default 20) frames of it, each moved by 0.1 A, are written as a dump
(columns id type x y z, atoms in a shuffled order as a parallel LAMMPS run writes them) into
bench-out/. molscope: `mol new x.lammpstrj waitfor all` (structure and every frame);
MDAnalysis: the Universe of the dump (LAMMPSDUMP topology) and iterating every frame. Both
with one thread (MOLSCOPE_THREADS=1, OMP_NUM_THREADS=1), each a process of its own timed
from outside: wall time and CPU time (user + system) of the whole process, best of REPEAT (3).

usage: bench_lammpstrj.py <srcdir> <builddir>   (NATOMS, NFRAMES, REPEAT override)"""
import os
import resource
import subprocess
import sys
import time
import warnings

MDA_READ = """
import sys, warnings
warnings.simplefilter("ignore")
import MDAnalysis as mda
u = mda.Universe(sys.argv[1], format="LAMMPSDUMP")
for ts in u.trajectory:
    pass
print("frames", len(u.trajectory))
"""


def make_dump(pdb, path, nframes):
    """The dump of nframes shifted copies of pdb's atoms, ids shuffled in every frame."""
    warnings.simplefilter("ignore")
    import numpy as np
    import MDAnalysis as mda
    pos = mda.Universe(pdb).atoms.positions.astype(np.float64)
    n = len(pos)
    lo, hi = pos.min(axis=0) - 1, pos.max(axis=0) + 1
    rng = np.random.default_rng(1)
    with open(path + ".part", "w") as f:
        for k in range(nframes):
            pos += 0.1
            order = rng.permutation(n)
            f.write("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%d\nITEM: BOX BOUNDS pp pp pp\n"
                    % (k * 1000, n))
            f.write("".join("%.6f %.6f\n" % (lo[d], hi[d] + 0.1 * k) for d in range(3)))
            f.write("ITEM: ATOMS id type x y z\n")
            rows = np.column_stack([order + 1, (order % 4) + 1, pos[order]])
            np.savetxt(f, rows, fmt="%d %d %.5f %.5f %.5f")
    os.rename(path + ".part", path)


def best_run(cmd, env, repeat):
    """(wall, cpu, frames) of the fastest of repeat runs of a command."""
    best = None
    for _ in range(repeat):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        out = subprocess.run(cmd, env=env, capture_output=True, text=True,
                             stdin=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        if out.returncode != 0 or "frames" not in out.stdout:
            sys.exit("failed: %s\n%s" % (" ".join(cmd), out.stderr[-500:]))
        frames = int(out.stdout.split("frames")[-1].split()[0])
        if best is None or wall < best[0]:
            best = (wall, cpu, frames)
    return best


def main():
    src, build = sys.argv[1], sys.argv[2]
    out = os.path.join(src, "bench-out")
    os.makedirs(out, exist_ok=True)
    natoms = int(os.environ.get("NATOMS", 1000000))
    nframes = int(os.environ.get("NFRAMES", 20))
    repeat = int(os.environ.get("REPEAT", 3))
    pdb = os.path.join(out, "xtc_%d.pdb" % natoms)
    dump = os.path.join(out, "lammps_%d_%d.lammpstrj" % (natoms, nframes))
    if not os.path.exists(pdb):
        subprocess.run(["python3", os.path.join(src, "scripts/bench/replicate.py"),
                        os.path.join(src, "tests/data/1tii.pdb"), str(natoms), pdb], check=True)
    if not os.path.exists(dump):
        make_dump(pdb, dump, nframes)
    with open(dump) as f:
        n = int([f.readline() for _ in range(4)][3])
    print("file: %s (%d atoms, %d frames, %d MB)" % (dump, n, nframes,
                                                      os.path.getsize(dump) >> 20))
    tcl = os.path.join(out, "bench_lammpstrj.tcl")
    with open(tcl, "w") as f:
        f.write("mol new %s type lammpstrj waitfor all\nputs \"frames [molinfo top get "
                "numframes]\"\nquit\n" % dump)
    env = dict(os.environ, MOLSCOPE_THREADS="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               MOLSCOPE_PLUGINDIR=os.path.join(build, "plugins/.libs"),
               MOLSCOPE_TCLLIB=os.path.join(src, "tcl"))
    ms = best_run([os.path.join(build, "src/molscope"), "-dispdev", "text", "-e", tcl], env,
                  repeat)
    md = best_run(["/usr/bin/python3", "-c", MDA_READ, dump], env, repeat)
    for name, (wall, cpu, frames) in (("molscope", ms), ("MDAnalysis", md)):
        print("%-11s %d frames: wall %.2f s, CPU %.2f s (%.1f M atom-frames/s wall)"
              % (name + ":", frames, wall, cpu, n * frames / wall / 1e6))
    print("ratio MDAnalysis / molscope: wall %.1fx, CPU %.1fx" % (md[0] / ms[0], md[1] / ms[1]))


if __name__ == "__main__":
    main()
