#!/usr/bin/python3
"""test_amber.py: the AMBER readers and writers against independent readers.
tests/tools/msdump -f loads files as `mol new` + `mol addfile` do and prints what it read
(atoms, types, charges, masses, atomic numbers, bonds, angles, dihedrals, impropers,
coordinates, velocities, cells, times). The files are made by tests/data/make/make_amber.py
with ParmEd, MDAnalysis and netCDF4.
- MDAnalysis' PRMTOP reader and msdump agree on helix.prmtop: names, types, charges (e),
  masses, atomic numbers, resids, resnames, bonds, angles, dihedrals and impropers; the
  old-layout helix_old.parm reads exactly like it.
- Coordinates to 1e-3 A and boxes: helix.rst7 and helix.inpcrd (MDAnalysis INPCRD; box,
  velocities and time from ParmEd), helix.mdcrd and helix.crdbox (MDAnalysis TRJ),
  helix.nc and helix_vel.nc (MDAnalysis NCDF: cells, times, velocities), helix.ncrst
  (ParmEd's NetCDF restart reader).
- msdump's NetCDF (with cell and with velocities) and crd/crdbox writers are read back by
  MDAnalysis.
The NetCDF checks SKIP when molscope was built without libnetcdf."""
import os
import subprocess
import sys

import mstest

R = mstest.Reporter("amber")
report = R.report


def dump(exe, files, extra=()):
    out = subprocess.run([exe, "-f"] + list(extra) + files, capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(out.stderr.strip())
    d = {"atoms": [], "props": [], "bonds": set(), "angle": set(), "dihedral": set(),
         "improper": [], "cells": [], "xyz": [], "vel": {}, "time": []}
    for line in out.stdout.splitlines():
        f = line.split("\t")
        if f[0] == "atom":
            d["atoms"].append((f[2], f[3], int(f[4])))
        elif f[0] == "prop":
            d["props"].append((f[2], float(f[3]), float(f[4]), int(f[5])))
        elif f[0] == "bond":
            d["bonds"].add((int(f[1]), int(f[2])))
        elif f[0] == "term":
            t = tuple(int(x) for x in f[2:])
            if f[1] == "improper":
                d["improper"].append(t)
            else:
                d[f[1]].add(canon(t))
        elif f[0] == "cell":
            d["cells"].append([float(x) for x in f[2:8]])
            d["xyz"].append([])
        elif f[0] == "xyz":
            d["xyz"][int(f[1])].append([float(x) for x in f[3:6]])
        elif f[0] == "vel":
            d["vel"].setdefault(int(f[1]), []).append([float(x) for x in f[3:6]])
        elif f[0] == "time":
            d["time"].append(float(f[2]))
    return d


def canon(t):
    """An angle or dihedral read either way round is the same one."""
    return min(tuple(t), tuple(reversed(t)))


def topology(mda, np, exe, p):
    u = mda.Universe(p("helix.prmtop"), format="PRMTOP", topology_format="PRMTOP")
    ours = dump(exe, [p("helix.prmtop")])
    a = u.atoms
    report(len(ours["atoms"]) == a.n_atoms == 392, "prmtop: 392 atoms", len(ours["atoms"]))
    report([x[0] for x in ours["atoms"]] == list(a.names), "prmtop: names")
    report([x[1] for x in ours["atoms"]] == list(a.resnames), "prmtop: resnames")
    report([x[2] for x in ours["atoms"]] == list(a.resids), "prmtop: resids")
    report([x[0] for x in ours["props"]] == list(a.types), "prmtop: types")
    q = np.array([x[1] for x in ours["props"]])
    report(float(np.abs(q - a.charges).max()) < 1e-6, "prmtop: charges (AMBER units / 18.2223)",
           float(np.abs(q - a.charges).max()))
    m = np.array([x[2] for x in ours["props"]])
    report(float(np.abs(m - a.masses).max()) < 1e-4, "prmtop: masses")
    z = [x[3] for x in ours["props"]]
    elements = {1: "H", 6: "C", 7: "N", 8: "O", 16: "S"}
    report([elements.get(k, "?") for k in z] == list(a.elements), "prmtop: atomic numbers")
    bonds = {tuple(sorted(b.indices)) for b in u.bonds}
    report(ours["bonds"] == bonds and len(bonds) == 399, "prmtop: 399 bonds",
           "%d vs %d" % (len(ours["bonds"]), len(bonds)))
    for kind, group in (("angle", u.angles), ("dihedral", u.dihedrals)):
        theirs = {canon(t.indices) for t in group}
        report(ours[kind] == theirs and len(theirs) > 0, "prmtop: %d %ss" % (len(theirs), kind),
               "ours %d, MDAnalysis %d" % (len(ours[kind]), len(theirs)))
    imp = sorted(tuple(int(i) for i in t.indices) for t in u.impropers)
    report(sorted(ours["improper"]) == imp and len(imp) > 0,
           "prmtop: %d impropers (negative fourth index)" % len(imp),
           "ours %d, MDAnalysis %d" % (len(ours["improper"]), len(imp)))
    old = dump(exe, [p("helix_old.parm")])
    same = all(old[k] == ours[k] for k in ("atoms", "props", "bonds", "angle", "dihedral",
                                             "improper"))
    report(same, "old-layout topology (helix_old.parm) reads like the new one")


def close(np, a, b, tol=1e-3):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and float(np.abs(a - b).max()) < tol


def restarts(mda, np, exe, p):
    import parmed
    for name, has_vel in (("helix.rst7", True), ("helix.inpcrd", False)):
        u = mda.Universe(p("helix.prmtop"), p(name), format="INPCRD")
        ours = dump(exe, [p("helix.prmtop"), p(name)])
        report(len(ours["xyz"]) == 1 and close(np, ours["xyz"][0], u.atoms.positions),
               "%s: coordinates as MDAnalysis reads them (1e-3 A)" % name)
        r = parmed.amber.Rst7(p(name))
        box = list(r.box) if r.hasbox else [0.0] * 6
        report(close(np, ours["cells"][0], box), "%s: box as ParmEd reads it" % name,
               "%s vs %s" % (ours["cells"][0], box))
        if has_vel:
            report(0 in ours["vel"] and close(np, ours["vel"][0], r.velocities, 1e-4),
                   "%s: velocities in A/ps as ParmEd reads them" % name)
            report(abs(ours["time"][0] - r.time) < 1e-6, "%s: time %g" % (name, r.time))
        else:
            report(not ours["vel"], "%s: no velocities" % name)


def ascii_trajectories(mda, np, exe, p, tmp):
    for name, boxed in (("helix.mdcrd", False), ("helix.crdbox", True)):
        u = mda.Universe(p("helix.prmtop"), p(name), format="TRJ")
        ours = dump(exe, [p("helix.prmtop"), p(name)])
        ref = [ts.positions.copy() for ts in u.trajectory]
        report(len(ours["xyz"]) == len(ref) == 5 and
               all(close(np, a, b) for a, b in zip(ours["xyz"], ref)),
               "%s: 5 frames as MDAnalysis TRJ reads them" % name)
        if boxed:
            dims = [ts.dimensions[:3].copy() for ts in u.trajectory]
            report(all(close(np, c[:3], d) for c, d in zip(ours["cells"], dims)),
                   "%s: box lengths of every frame" % name)
        out = tmp("ours_" + name)
        subprocess.run([exe, "-o", out, p("helix.prmtop"), p(name)], check=True,
                       capture_output=True)
        v = mda.Universe(p("helix.prmtop"), out, format="TRJ")
        back = [ts.positions.copy() for ts in v.trajectory]
        report(len(back) == 5 and all(close(np, a, b) for a, b in zip(back, ref)),
               "msdump's %s read back by MDAnalysis" % name.split(".")[1])


def netcdf(mda, np, exe, p, tmp):
    u = mda.Universe(p("helix.prmtop"), p("helix.nc"))
    ours = dump(exe, [p("helix.prmtop"), p("helix.nc")])
    ref = [(ts.positions.copy(), ts.dimensions.copy(), ts.time) for ts in u.trajectory]
    report(len(ours["xyz"]) == 10 and all(close(np, a, r[0]) for a, r in zip(ours["xyz"], ref)),
           "helix.nc: 10 frames as MDAnalysis NCDF reads them")
    report(all(close(np, c, r[1]) for c, r in zip(ours["cells"], ref)),
           "helix.nc: cell lengths and angles of every frame")
    report(all(abs(t - r[2]) < 1e-4 for t, r in zip(ours["time"], ref)), "helix.nc: times")
    step = dump(exe, [p("helix.prmtop"), p("helix.nc")], ["-s", "3"])
    report(len(step["xyz"]) == 4 and all(close(np, step["xyz"][k], ref[3 * k][0])
                                         for k in range(4)),
           "helix.nc: every third frame (0 3 6 9)")
    v = mda.Universe(p("helix.prmtop"), p("helix_vel.nc"))
    vo = dump(exe, [p("helix.prmtop"), p("helix_vel.nc")])
    vref = [(ts.velocities.copy(), ts.time) for ts in v.trajectory]
    report(len(vo["vel"]) == 3 and all(close(np, vo["vel"][k], vref[k][0], 1e-4)
                                       for k in range(3)),
           "helix_vel.nc: velocities (scale_factor applied) as MDAnalysis reads them")
    report([round(t, 4) for t in vo["time"]] == [round(float(r[1]), 4) for r in vref],
           "helix_vel.nc: times", "%s" % vo["time"])
    import parmed
    r = parmed.amber.NetCDFRestart.open_old(p("helix.ncrst"))
    rs = dump(exe, [p("helix.prmtop"), p("helix.ncrst")])
    report(close(np, rs["xyz"][0], r.coordinates.reshape(-1, 3)) and
           close(np, rs["cells"][0], list(r.cell_lengths) + list(r.cell_angles)) and
           close(np, rs["vel"][0], r.velocities.reshape(-1, 3), 1e-4),
           "helix.ncrst: coordinates, box and velocities as ParmEd reads them")
    for src, what in (("helix.nc", "cells"), ("helix_vel.nc", "velocities")):
        out = tmp("ours_" + src)
        subprocess.run([exe, "-o", out, p("helix.prmtop"), p(src)], check=True,
                       capture_output=True)
        w = mda.Universe(p("helix.prmtop"), out)
        orig = mda.Universe(p("helix.prmtop"), p(src))
        ok = len(w.trajectory) == len(orig.trajectory)
        for a, b in zip(w.trajectory, orig.trajectory):
            a_, b_ = (a.velocities, b.velocities) if what == "velocities" else \
                (a.dimensions, b.dimensions)
            ok = ok and close(np, a.positions, b.positions, 1e-4) and close(np, a_, b_, 1e-4)
            ok = ok and abs(a.time - b.time) < 1e-4
        report(ok, "msdump's NetCDF (%s) read back by MDAnalysis" % what)


def main():
    mods = R.imports(["numpy", "MDAnalysis", "parmed"], "python3-mdanalysis or python3-parmed")
    if mods is None:
        return 0
    np, mda = mods[:2]
    _, builddir, data, outdir = mstest.dirs()
    exe = R.msdump_exe(builddir)
    if exe is None:
        return 1
    p = lambda f: os.path.join(data, f)
    tmp = lambda f: os.path.join(outdir, "amber_%d_%s" % (os.getpid(), f))
    with open(os.path.join(builddir, "config.h")) as f:
        have_nc = "#define MS_HAVE_NETCDF 1" in f.read()
    steps = [lambda: topology(mda, np, exe, p), lambda: restarts(mda, np, exe, p),
             lambda: ascii_trajectories(mda, np, exe, p, tmp)]
    if have_nc:
        steps.append(lambda: netcdf(mda, np, exe, p, tmp))
    else:
        R.skip("netcdf", "molscope was built without libnetcdf")
    return R.steps(steps)


if __name__ == "__main__":
    sys.exit(main())
