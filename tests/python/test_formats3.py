#!/usr/bin/python3
"""test_formats3.py: the VASP, CHARMM and DMS readers and writers against independent ones.
molscope itself loads each file (a Tcl script prints what it read); then
- ase (python3-ase) reads the same POSCAR/CONTCAR/XDATCAR files: cell lengths and angles,
  species and positions within 1e-3 A, frame by frame; ase reads the POSCAR molscope writes
  of each like the original;
- MDAnalysis reads the CHARMM crd files (standard and EXT) and the DMS file: names,
  resnames, resids, segids, weights, masses, charges, bonds, velocities, positions, cells;
  MDAnalysis reads molscope's own crd (both layouts) and DMS of helix.psf + helix.dcd like
  molscope reads the sources.
Prints PASS:/FAIL:/SKIP: lines; SKIP when a peer is missing."""
import os
import subprocess
import sys

import mstest

R = mstest.Reporter("formats3")
report = R.report
TOL = 1e-3

TCL = r"""
proc dump {m} {
    set s [atomselect $m all]
    puts "natoms\t[molinfo $m get numatoms]"
    foreach a [$s get {name resname resid segname mass charge beta element}] {
        puts "atom\t[join $a \t]"
    }
    foreach i [$s list] b [$s getbonds] o [$s getbondorders] {
        foreach j $b k $o { if {$j > $i} { puts "bond\t$i\t$j\t$k" } }
    }
    for {set k 0} {$k < [molinfo $m get numframes]} {incr k} {
        animate goto $k
        $s frame $k
        puts "cell\t[join [molinfo $m get {a b c alpha beta gamma}] \t]"
        foreach p [$s get {x y z}] v [$s get {vx vy vz}] { puts "xyz\t$k\t[join $p \t]\t[join $v \t]" }
    }
}
"""


def molscope(script):
    """Run molscope on a Tcl script; return its output lines."""
    exe = os.environ.get("MOLSCOPE", "")
    r = subprocess.run([exe, "-dispdev", "text", "-e", "/dev/stdin"], input=TCL + script + "\nquit\n",
                       capture_output=True, text=True)
    if r.returncode != 0 or "error" in r.stdout.lower().split("\n")[-2:]:
        raise RuntimeError(r.stderr.strip() or r.stdout[-500:])
    return r.stdout.splitlines()


def load(files, write=None):
    """files: [(path, type or None)]: the first makes the molecule, the rest are added.
    With write (path, type) the molecule's selection `all` is written there first."""
    script = []
    for k, (f, t) in enumerate(files):
        ty = " type %s" % t if t else ""
        if k == 0:
            script.append("set m [mol new {%s}%s waitfor all]" % (f, ty))
        else:
            script.append("mol addfile {%s}%s waitfor all $m" % (f, ty))
    if write:
        script.append("animate write %s {%s} beg 0 end 0 $m" % (write[1], write[0]))
        return molscope("\n".join(script))
    script.append("dump $m")
    d = {"atoms": [], "bonds": [], "cells": [], "xyz": [], "vel": []}
    for line in molscope("\n".join(script)):
        f = line.split("\t")
        if f[0] == "atom":
            d["atoms"].append(f[1:])
        elif f[0] == "bond":
            d["bonds"].append((int(f[1]), int(f[2]), float(f[3])))
        elif f[0] == "cell":
            d["cells"].append([float(x) for x in f[1:]])
            d["xyz"].append([])
            d["vel"].append([])
        elif f[0] == "xyz":
            d["xyz"][int(f[1])].append([float(x) for x in f[2:5]])
            d["vel"][int(f[1])].append([float(x) for x in f[5:8]])
    return d


def worst(np, a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.abs(a - b).max()) if a.shape == b.shape else float("inf")


def vasp_compare(np, name, ours, images):
    report(len(ours["xyz"]) == len(images), "%s: %d frames" % (name, len(images)),
           "molscope read %d" % len(ours["xyz"]))
    sym = [a[0] for a in ours["atoms"]]
    report(sym == images[0].get_chemical_symbols(), "%s: species" % name,
           "%s vs %s" % (sym[:6], images[0].get_chemical_symbols()[:6]))
    dx = max(worst(np, x, im.positions) for x, im in zip(ours["xyz"], images))
    dc = max(worst(np, c, im.cell.cellpar()) for c, im in zip(ours["cells"], images))
    report(dx <= TOL, "%s: positions of every frame within %g A" % (name, TOL), "largest %g" % dx)
    report(dc <= TOL, "%s: cell lengths and angles of every frame" % name, "largest %g" % dc)


def vasp(np, p, tmp):
    try:
        import ase.io
    except ImportError:
        R.skip("VASP", "python3-ase is not installed")
        return
    cases = [("POSCAR_spc", "POSCAR_spc", "vasp"), ("CONTCAR_pept", "CONTCAR_pept", "vasp"),
             ("POSCAR4_pept", "POSCAR4_pept", "vasp"),
             ("POSCAR_negscale (as ase reads POSCAR_spc)", "POSCAR_spc", "vasp"),
             ("XDATCAR_spc", "XDATCAR_spc", "vasp-xdatcar"),
             ("XDATCAR_npt", "XDATCAR_npt", "vasp-xdatcar")]
    for name, ref, fmt in cases:
        f = name.split(" ")[0]
        try:
            ours = load([(p(f), None)])
        except RuntimeError as e:
            report(False, "%s: molscope reads it" % name, str(e))
            continue
        vasp_compare(np, name, ours, ase.io.read(p(ref), index=":", format=fmt))
    for f in ("CONTCAR_pept", "POSCAR_spc"):
        out = tmp("POSCAR_written_" + f)
        try:
            load([(p(f), None)], write=(out, "POSCAR"))
            ours = load([(p(f), None)])
        except RuntimeError as e:
            report(False, "POSCAR written from %s" % f, str(e))
            continue
        vasp_compare(np, "POSCAR written from %s, read by ase" % f, ours,
                     ase.io.read(out, index=":", format="vasp"))


def mda_compare(np, name, ours, u, fields=("names", "resnames", "resids", "segids"), cell=True,
                bonds=False, masses=False, velocities=False, beta=False):
    got = {"names": [a[0] for a in ours["atoms"]], "resnames": [a[1] for a in ours["atoms"]],
           "resids": [int(a[2]) for a in ours["atoms"]], "segids": [a[3] for a in ours["atoms"]]}
    for fld in fields:
        ref = [str(x) if fld != "resids" else int(x) for x in getattr(u.atoms, fld)]
        report(got[fld] == ref, "%s: %s" % (name, fld), "%s vs %s" % (got[fld][:5], ref[:5]))
    report(worst(np, ours["xyz"][0], u.atoms.positions) <= TOL,
           "%s: positions within %g A" % (name, TOL),
           "largest %g" % worst(np, ours["xyz"][0], u.atoms.positions))
    if cell:
        report(worst(np, ours["cells"][0], u.dimensions) <= TOL, "%s: cell" % name,
               "%s vs %s" % (ours["cells"][0], u.dimensions))
    if masses:
        for k, fld in ((4, "masses"), (5, "charges")):
            d = worst(np, [float(a[k]) for a in ours["atoms"]], getattr(u.atoms, fld))
            report(d <= 1e-4, "%s: %s" % (name, fld), "largest difference %g" % d)
    if beta:
        d = worst(np, [float(a[6]) for a in ours["atoms"]], u.atoms.tempfactors)
        report(d <= 1e-4, "%s: weights as beta" % name, "largest difference %g" % d)
    if bonds:
        mine = sorted((i, j) for i, j, _ in ours["bonds"])
        ref = sorted(tuple(sorted(b)) for b in u.bonds.indices.tolist())
        report(mine == ref, "%s: %d bonds" % (name, len(ref)), "%d vs %d" % (len(mine), len(ref)))
    if velocities:
        d = worst(np, ours["vel"][0], u.atoms.velocities)
        report(d <= TOL, "%s: velocities" % name, "largest difference %g" % d)


def dms_cell(np, path):
    """a b c alpha beta gamma of a DMS file's global_cell rows."""
    import sqlite3
    with sqlite3.connect(path) as db:
        v = np.array(db.execute("SELECT x, y, z FROM global_cell ORDER BY id").fetchall())
    ln = np.linalg.norm(v, axis=1)
    ang = lambda i, j: np.degrees(np.arccos(np.dot(v[i], v[j]) / (ln[i] * ln[j])))
    return list(ln) + [ang(1, 2), ang(0, 2), ang(0, 1)]


def charmm_dms(np, mda, p, tmp):
    plugdir = os.environ.get("MOLSCOPE_PLUGINDIR", "")
    have_dms = os.path.exists(os.path.join(plugdir, "dms.so"))
    if not have_dms:
        R.skip("DMS", "the dms plugin is not built (configure found no SQLite)")
    for f in ("helix.crd", "helix_ext.crd"):
        try:
            ours = load([(p(f), "cor")])
        except RuntimeError as e:
            report(False, "%s: molscope reads it" % f, str(e))
            continue
        mda_compare(np, f, ours, mda.Universe(p(f)), cell=False, beta=True)
    try:
        if not have_dms:
            raise StopIteration
        ours = load([(p("pept.dms"), None)])
        u = mda.Universe(p("pept.dms"))
        mda_compare(np, "pept.dms", ours, u, bonds=True, masses=True, velocities=True)
        orders = {(i, j): o for i, j, o in ours["bonds"]}
        import sqlite3   # MDAnalysis keeps no bond orders: the table itself is the reference
        with sqlite3.connect(p("pept.dms")) as db:
            ref = {tuple(sorted(r[:2])): float(r[2])
                   for r in db.execute('SELECT p0, p1, "order" FROM bond')}
        report(orders == ref and sorted(set(ref.values())) == [1.0, 2.0],
               "pept.dms: bond orders (1 and 2) as the bond table gives them",
               "%d of %d differ" % (sum(orders.get(k) != v for k, v in ref.items()), len(ref)))
    except StopIteration:
        pass
    except RuntimeError as e:
        report(False, "pept.dms: molscope reads it", str(e))
    src = [(p("helix.psf"), None), (p("helix.dcd"), None)]
    for name, out, ty, kw in (("crd written by molscope", tmp("w.cor"), "cor", {"format": "CRD"}),
                              ("DMS written by molscope", tmp("w.dms"), "dms", {})):
        if ty == "dms" and not have_dms:
            continue
        try:
            load(src, write=(out, ty))
            ours = load(src)
        except RuntimeError as e:
            report(False, "%s: molscope writes it" % name, str(e))
            continue
        ours["xyz"], ours["cells"], ours["vel"] = ours["xyz"][:1], ours["cells"][:1], ours["vel"][:1]
        u = mda.Universe(out, **kw)
        # MDAnalysis reads global_cell's columns as the box vectors (rows in DMS files): its
        # cell is only right for a rectangular box, so the rows are checked here instead
        mda_compare(np, name, ours, u, cell=False, bonds=ty == "dms", masses=ty == "dms")
        if ty == "dms":
            report(worst(np, dms_cell(np, out), ours["cells"][0]) <= TOL,
                   "%s: global_cell rows are the box vectors of the cell" % name,
                   "%s vs %s" % (dms_cell(np, out), ours["cells"][0]))
    # EXT: a name longer than 4 characters makes molscope write the extended layout
    ext = tmp("w_ext.cor")
    try:
        molscope("set m [mol new {%s}]\nmol addfile {%s} last 0 $m\n"
                 "[atomselect $m \"index 0\"] set name LONGNAME\n"
                 "animate write cor {%s} beg 0 end 0 $m\n" % (p("helix.psf"), p("helix.dcd"), ext))
        u = mda.Universe(ext, format="CRD")
        head = open(ext).read().split("\n")[2]
        report(head.strip().endswith("EXT") and u.atoms.names[0] == "LONGNAME" and
               u.atoms.n_atoms == 392, "EXT crd written by molscope: MDAnalysis reads it",
               "%r %s %d" % (head, u.atoms.names[0], u.atoms.n_atoms))
    except (RuntimeError, ValueError, OSError) as e:
        report(False, "EXT crd written by molscope", str(e))


def main():
    mods = R.imports(["numpy", "MDAnalysis"], "python3-mdanalysis")
    if mods is None:
        return 0
    np, mda = mods
    _, _, data, outdir = mstest.dirs()
    if not os.access(os.environ.get("MOLSCOPE", ""), os.X_OK):
        print("FAIL: %s: $MOLSCOPE is not a program (run through tests/run-tests)" % R.suite)
        return 1
    p = lambda f: os.path.join(data, f)
    tmp = lambda f: os.path.join(outdir, "formats3_%d_%s" % (os.getpid(), f))
    vasp(np, p, tmp)
    charmm_dms(np, mda, p, tmp)
    return 1 if R.failures else 0


if __name__ == "__main__":
    sys.exit(main())
