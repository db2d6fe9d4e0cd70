#!/usr/bin/python3
"""test_mdanalysis.py: molscope's readers and writers against an independent reader.
tests/tools/msdump loads each file set as `mol new` + `mol addfile` do and prints what it
read; Debian's python3-mdanalysis reads the same files; the two must agree on atom and frame
counts, names, residue names, resids, segment names (PSF), coordinates to 1e-3 A and unit
cells. Then msdump writes PSF, DCD, GRO, PDB and XYZ files and MDAnalysis reads them back
against molscope's reading of the originals. Prints PASS:/FAIL:/SKIP: lines; SKIP when
MDAnalysis is not installed."""
import os
import subprocess
import sys

import mstest

R = mstest.Reporter("mdanalysis")
report = R.report
msdump = mstest.msdump
TOL = 1e-3


def compare_atoms(name, ours, u, segids):
    """Names, residue names, resids and (PSF) segment names, atom by atom."""
    names, resids = u.atoms.names, u.atoms.resids
    resnames = u.atoms.resnames if hasattr(u.atoms, "resnames") else None  # XYZ has none
    bad = [i for i, a in enumerate(ours["atoms"])
           if a[0] != names[i] or a[2] != resids[i]
           or (resnames is not None and a[1] != resnames[i])]
    what = "names, residue names and resids" if resnames is not None else "names and resids"
    report(not bad, "%s: %s" % (name, what),
           "first difference at atom %d: %s vs %s %s %s" % (
               bad[0], ours["atoms"][bad[0]][:3], names[bad[0]],
               resnames[bad[0]] if resnames is not None else "-", resids[bad[0]]) if bad else "")
    if segids:
        segs = u.atoms.segids
        bad = [i for i, a in enumerate(ours["atoms"]) if a[3] != segs[i]]
        report(not bad, "%s: segment names" % name,
               "atom %d: %s vs %s" % (bad[0], ours["atoms"][bad[0]][3], segs[bad[0]])
               if bad else "")


def compare(name, ours, u, skip_frames=0, segids=False, cells=True, names=True):
    """ours: msdump's reading; u: an MDAnalysis Universe of the same files. skip_frames:
    frames molscope has before the trajectory (a PDB's own coordinates)."""
    import numpy as np

    n = u.atoms.n_atoms
    nf = len(u.trajectory)
    report(ours["natoms"] == n and ours["nframes"] - skip_frames == nf,
           "%s: %d atoms, %d frames" % (name, n, nf),
           "molscope has %d atoms, %d frames" % (ours["natoms"], ours["nframes"] - skip_frames))
    if ours["natoms"] != n or ours["nframes"] - skip_frames != nf:
        return
    if names:
        compare_atoms(name, ours, u, segids)
    worst, worst_cell = 0.0, 0.0
    for k, ts in enumerate(u.trajectory):
        mine = np.array(ours["xyz"][k + skip_frames])
        worst = max(worst, float(np.abs(mine - u.atoms.positions).max()))
        if cells and ts.dimensions is not None:
            worst_cell = max(worst_cell, float(np.abs(
                np.array(ours["cells"][k + skip_frames]) - ts.dimensions).max()))
    report(worst <= TOL, "%s: coordinates of every frame within %g A" % (name, TOL),
           "largest difference %g A" % worst)
    if cells:
        report(worst_cell <= TOL, "%s: unit cells" % name, "largest difference %g" % worst_cell)


def main():
    mods = R.imports(["MDAnalysis"], "python3-mdanalysis")
    if mods is None:
        return 0
    mda, = mods
    _, builddir, data, _ = mstest.dirs()
    exe = R.msdump_exe(builddir)
    if exe is None:
        return 1
    p = lambda f: os.path.join(data, f)
    cases = [
        # name, msdump files, MDAnalysis arguments, frames before the trajectory, options
        ("1tii.pdb", [p("1tii.pdb")], [p("1tii.pdb")], 0, {}),
        ("il2.pdb", [p("il2.pdb")], [p("il2.pdb")], 0, {}),
        ("pept.pdb", [p("pept.pdb")], [p("pept.pdb")], 0, {}),
        ("helix.psf + helix.dcd", [p("helix.psf"), p("helix.dcd")],
         [p("helix.psf"), p("helix.dcd")], 0, {"segids": True}),
        ("helix_amber.pdb + helix.dcd", [p("helix_amber.pdb"), p("helix.dcd")],
         [p("helix_amber.pdb"), p("helix.dcd")], 1, {}),
        ("big-endian DCD", [p("helix.psf"), p("helix_be.dcd")],
         [p("helix.psf"), p("helix_be.dcd")], 0, {"segids": True}),
        ("fixed-atom DCD", [p("helix.psf"), p("helix_fixed.dcd")],
         [p("helix.psf"), p("helix_fixed.dcd")], 0, {"cells": False}),
        ("X-PLOR DCD", [p("helix.psf"), p("helix_xplor.dcd")],
         [p("helix.psf"), p("helix_xplor.dcd")], 0, {"cells": False}),
        ("spc216.gro", [p("spc216.gro")], [p("spc216.gro")], 0, {}),
        ("helix.gro", [p("helix.gro")], [p("helix.gro")], 0, {}),
        ("helix.xyz", [p("helix.xyz")], [p("helix.xyz")], 0, {"cells": False}),
    ]
    for name, files, mda_args, skip, opts in cases:
        try:
            ours = msdump(exe, files)
        except RuntimeError as e:
            report(False, "%s: msdump reads it" % name, str(e))
            continue
        u = mda.Universe(*mda_args)
        compare(name, ours, u, skip, **opts)
    check_writers(mda, exe, p, os.environ.get("MS_TEST_OUT", "/tmp"))
    return 1 if R.failures else 0


def check_writers(mda, exe, p, outdir):
    """msdump writes each format; MDAnalysis reads the result; it must match molscope's
    reading of the source files."""
    out = lambda ext: os.path.join(outdir, "mda_written_%d.%s" % (os.getpid(), ext))
    cases = [
        # name, source files, written file, MDAnalysis arguments given the written path
        ("written DCD", [p("helix.psf"), p("helix.dcd")], out("dcd"),
         lambda w: [p("helix.psf"), w], {"segids": True}),
        ("written PSF", [p("helix.psf"), p("helix.dcd")], out("psf"),
         lambda w: [w, p("helix.dcd")], {"segids": True}),
        ("written GRO", [p("helix.gro")], out("gro"), lambda w: [w], {}),
        ("written PDB", [p("helix.psf"), p("helix.dcd")], out("pdb"), lambda w: [w], {}),
        ("written XYZ", [p("helix.psf"), p("helix.dcd")], out("xyz"), lambda w: [w],
         {"cells": False, "names": False}),  # XYZ holds element symbols, no residues
    ]
    for name, files, written, mda_args, opts in cases:
        try:
            ours = msdump(exe, files)
            subprocess.run([exe, "-o", written] + files, check=True, capture_output=True)
        except (RuntimeError, subprocess.CalledProcessError) as e:
            report(False, "%s: msdump writes it" % name, str(e))
            continue
        compare(name, ours, mda.Universe(*mda_args(written)), 0, **opts)
        if name == "written PSF":
            bonds = lambda u: sorted(tuple(sorted(b)) for b in u.bonds.indices.tolist())
            report(bonds(mda.Universe(written)) == bonds(mda.Universe(p("helix.psf"))),
                   "written PSF: the same 399 bonds as the original")
        os.remove(written)


if __name__ == "__main__":
    sys.exit(main())
