#!/usr/bin/python3
"""pymol_gaussian.py: PyMOL's side of the QuickSurf benchmark.

    pymol_gaussian.py structure.pdb spacing

Loads the structure, computes a Gaussian map at the given spacing (cmd.map_new) and its
isosurface (cmd.isosurface, forced by asking for its extent), and prints one line:
    pymol atoms=N load_s=.. map_s=.. iso_s=.. total_s=.. maxrss_mb=..
PyMOL's Gaussian map has its own widths and scale (from B-factors and radii), so the level
is PyMOL's default of 1.0: the comparison is of the time to build a map and a surface of
the same structure at the same spacing, not of identical surfaces.
"""
import resource
import sys
import time

from pymol import cmd


def main():
    path, spacing = sys.argv[1], float(sys.argv[2])
    t0 = time.time()
    cmd.load(path, "mol")
    t1 = time.time()
    cmd.map_new("dens", "gaussian", spacing, "mol")
    t2 = time.time()
    cmd.isosurface("surf", "dens", 1.0)
    cmd.refresh()
    cmd.get_extent("surf")
    t3 = time.time()
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print("pymol atoms=%d load_s=%.2f map_s=%.2f iso_s=%.2f total_s=%.2f maxrss_mb=%.0f"
          % (cmd.count_atoms("mol"), t1 - t0, t2 - t1, t3 - t2, t3 - t1, rss))


if __name__ == "__main__":
    main()
