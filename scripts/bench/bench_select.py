#!/usr/bin/env python3
"""bench_select.py: the selection benchmark. Builds systems of about N atoms by replicating
tests/data/1tii.pdb on a lattice (scripts/bench/replicate.py; the PDB goes to bench-out/),
times molscope's selections (bench_select.tcl, through the binary) and MDAnalysis'
equivalents on the same file's coordinates in the same run, checks that both select the
same number of atoms, and prints a table with the ratios.

usage: bench_select.py [--repeat R] N [N ...]      (e.g. 1000000 2000000)

Times are medians of R runs (the best is printed too). The machine may be shared: molscope
loads every size in one process and runs each selection on the sizes in turn, so a burst of
someone else's load does not land on one size only."""
import os
import subprocess
import sys
import time
import warnings

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# MDAnalysis' selections with the same meaning as bench_select.sels. VMD's `within d of S`
# includes S; MDAnalysis' `around` excludes it, hence the `or`.
MDA = {
    "within": "(around 5 index 0:999) or index 0:999",
    "sameres": "byres ((around 3 index 0:999) or index 0:999)",
    "boolean10": "(name CA or name CB or name N) and (resname ALA or resname GLY or resname LEU)"
                 " and not resname HOH and resid 10:200 and chainID A D and prop x > 100",
}


def hy36_decode(field):
    """Integer of a PDB number field in decimal or hybrid-36 (upper case)."""
    field = field.strip()
    try:
        return int(field)
    except ValueError:
        width = len(field)
        return int(field, 36) - 10 * 36 ** (width - 1) + 10 ** width


def read_pdb(path):
    """records[i] = (name, resname, chain, resid, segid), xyz[i] = (x, y, z)."""
    records, xyz = [], []
    for l in open(path):
        if l.startswith(("ATOM  ", "HETATM")):
            records.append((l[12:16].strip(), l[17:21].strip(), l[21], hy36_decode(l[22:26]),
                            l[72:76].strip()))
            xyz.append((float(l[30:38]), float(l[38:46]), float(l[46:54])))
    return records, xyz


def build_universe(records, xyz):
    """An MDAnalysis Universe of the same atoms, residues as molscope makes them (runs of
    atoms sharing resid, chain and segment)."""
    import MDAnalysis as mda
    import numpy as np
    resindex, residues, segindex = [], [], {}
    key_prev = None
    for rec in records:
        key = (rec[3], rec[2], rec[4])
        if key != key_prev:
            residues.append(rec)
            key_prev = key
        resindex.append(len(residues) - 1)
    for r in residues:
        segindex.setdefault(r[4], len(segindex))
    u = mda.Universe.empty(len(records), n_residues=len(residues), n_segments=len(segindex),
                           atom_resindex=np.array(resindex),
                           residue_segindex=np.array([segindex[r[4]] for r in residues]),
                           trajectory=True)
    u.add_TopologyAttr("name", [r[0] for r in records])
    u.add_TopologyAttr("chainIDs", [r[2] for r in records])
    u.add_TopologyAttr("resname", [r[1] for r in residues])
    u.add_TopologyAttr("resid", [r[3] for r in residues])
    u.add_TopologyAttr("segid", list(segindex))
    u.atoms.positions = np.array(xyz, dtype=np.float32)
    return u


def median(xs):
    xs = sorted(xs)
    n = len(xs)
    return xs[n // 2] if n % 2 else (xs[n // 2 - 1] + xs[n // 2]) / 2


def time_mda(u, text, repeat):
    times, n = [], 0
    for _ in range(repeat):
        t0 = time.perf_counter()
        n = len(u.select_atoms(text))
        times.append((time.perf_counter() - t0) * 1e3)
    return median(times), min(times), n


def run_molscope(pdbs, repeat):
    """{(natoms, label): (median ms, best ms, count)} from one molscope process."""
    env = dict(os.environ, BENCH_PDBS=" ".join(pdbs), BENCH_REPEAT=str(repeat),
               MOLSCOPE_TCLLIB=os.path.join(ROOT, "tcl"))
    out = subprocess.run([os.path.join(ROOT, "src", "molscope"), "-dispdev", "text", "-e",
                          os.path.join(HERE, "bench_select.tcl")], env=env, check=True,
                         stdin=subprocess.DEVNULL, capture_output=True, text=True).stdout
    rows = {}
    for line in out.splitlines():
        f = line.split("\t")
        if len(f) == 5:
            rows[(int(f[0]), f[1])] = (float(f[2]), float(f[3]), int(f[4]))
    return rows


def main():
    args = sys.argv[1:]
    repeat = 15
    if args[:1] == ["--repeat"]:
        repeat, args = int(args[1]), args[2:]
    sizes = [int(a) for a in args] or [1000000, 2000000]
    os.makedirs(os.path.join(ROOT, "bench-out"), exist_ok=True)
    pdbs = {}
    for n in sizes:
        pdbs[n] = os.path.join(ROOT, "bench-out", "select%d.pdb" % n)
        if not os.path.exists(pdbs[n]):
            subprocess.run([sys.executable, os.path.join(HERE, "replicate.py"),
                            os.path.join(ROOT, "tests", "data", "1tii.pdb"), str(n), pdbs[n]],
                           check=True, stdout=subprocess.DEVNULL)
    ms = run_molscope([pdbs[n] for n in sizes], repeat)
    results = {}
    natoms = {}
    for n in sizes:
        records, xyz = read_pdb(pdbs[n])
        natoms[n] = len(records)
        u = build_universe(records, xyz)
        n = len(records)   # replicate.py writes whole copies: slightly more than asked
        for label, text in MDA.items():
            t, tbest, count = time_mda(u, text, repeat)
            mt, mbest, mcount = ms[(n, label)]
            results[(n, label)] = mt
            same = "same" if count == mcount else "DIFFERENT (%d vs %d)" % (mcount, count)
            print("%9d atoms %-10s molscope %7.2f ms (best %7.2f)  MDAnalysis %7.1f ms "
                  "(best %7.1f)  ratio %4.0fx  %d atoms, %s"
                  % (n, label, mt, mbest, t, tbest, t / mt, mcount, same), flush=True)
        print("%9d atoms load: molscope %.0f ms" % (n, ms[(n, "load")][0]), flush=True)
    if len(sizes) >= 2:
        a, b = natoms[sizes[0]], natoms[sizes[-1]]
        for label in MDA:
            print("scaling %-10s molscope %d -> %d atoms: %.2fx time (medians)"
                  % (label, a, b, results[(b, label)] / results[(a, label)]))


if __name__ == "__main__":
    main()
