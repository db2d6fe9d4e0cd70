#!/usr/bin/python3
"""test_lammps.py: the LAMMPS plugins and topotools' LAMMPS files against MDAnalysis
(python3-mdanalysis: its LAMMPS DATA parser and reader, and its DUMP reader).
- helix.data (written by MDAnalysis, tests/data/make/make_lammps.py): molscope's reading
  agrees with MDAnalysis' on counts of atoms, bonds, angles, dihedrals and impropers, atom
  types, charges, masses, molecule ids, bonds with their types, every angle, dihedral and
  improper with its type, coordinates to 1e-3 A and the box.
- the dumps: every frame's coordinates to 1e-3 A and boxes. MDAnalysis sorts atoms by id
  like molscope and moves the box origin (xlo ylo zlo) to 0, so molscope's positions less
  the origin are compared. MDAnalysis 2.4.2 gets two things wrong that molscope gets right:
  it subtracts the origin from scaled coordinates that never had it added, and it unwraps
  image flags with the box lengths alone (no tilt). So helix_xu.lammpstrj (unwrapped) is
  compared with MDAnalysis' reading of it, the wrapped, scaled and scaled-unwrapped
  triclinic dumps of the same frames with that same reading, and helix_ortho.lammpstrj
  (wrapped + image flags, orthogonal box) with MDAnalysis' unwrap_images reading of it.
- molscope's `topo writelammpsdata` (styles full and atomic) read back by MDAnalysis:
  counts, types, charges, coordinates and box.
molscope's side comes from a Tcl script run by the molscope program. Prints PASS:/FAIL:/
SKIP: lines; SKIP when MDAnalysis is missing."""
import os
import subprocess
import sys
import tempfile
import warnings

import mstest

R = mstest.Reporter("lammps")
report = R.report
TOL = 1e-3

DUMP_SCRIPT = r"""
package require topotools
proc dump {m} {
    puts "natoms\t[molinfo $m get numatoms]"
    foreach a [[atomselect $m all] get {type resid charge mass}] { puts "atom\t[join $a \t]" }
    foreach b [topo -molid $m getbondlist type] { puts "bond\t[join $b \t]" }
    foreach k {angle dihedral improper} {
        foreach t [topo -molid $m get${k}list] { puts "$k\t[join $t \t]" }
    }
    for {set f 0} {$f < [molinfo $m get numframes]} {incr f} {
        molinfo $m set frame $f
        puts "cell\t[join [molinfo $m get {a b c alpha beta gamma}] \t]"
        foreach p [[atomselect $m all frame $f] get {x y z}] { puts "xyz\t$f\t[join $p \t]" }
    }
}
foreach {cmd file} $argv {
    if {$cmd eq "write"} {
        lassign [split $file ,] src out style
        topo -molid [topo readlammpsdata $src] writelammpsdata $out $style
        continue
    }
    dump [mol new $file type $cmd waitfor all]
}
"""


def molscope(files):
    """What molscope reads of each (type, file) pair, or does for ("write", "src,out,style")."""
    with tempfile.NamedTemporaryFile("w", suffix=".tcl", delete=False) as f:
        f.write(DUMP_SCRIPT)
        script = f.name
    args = [a for pair in files for a in pair]
    try:
        r = subprocess.run([os.environ.get("MOLSCOPE", "molscope"), "-dispdev", "text", "-e",
                            script, "-eofexit", "-args"] + args, capture_output=True,
                           text=True, stdin=subprocess.DEVNULL)
    finally:
        os.unlink(script)
    if r.returncode != 0 or "Error" in r.stderr:
        raise RuntimeError(r.stderr.strip()[-400:])
    out = []
    for line in r.stdout.splitlines():
        f = line.split("\t")
        if f[0] == "natoms":
            out.append({"natoms": int(f[1]), "atoms": [], "bond": [], "angle": [],
                        "dihedral": [], "improper": [], "cells": [], "xyz": []})
        elif f[0] == "atom":
            out[-1]["atoms"].append((f[1], int(f[2]), float(f[3]), float(f[4])))
        elif f[0] == "bond":
            out[-1]["bond"].append((int(f[1]), int(f[2]), f[3]))
        elif f[0] in ("angle", "dihedral", "improper"):
            out[-1][f[0]].append((f[1],) + tuple(int(x) for x in f[2:]))
        elif f[0] == "cell":
            out[-1]["cells"].append([float(x) for x in f[1:7]])
            out[-1]["xyz"].append([])
        elif f[0] == "xyz":
            out[-1]["xyz"][int(f[1])].append([float(x) for x in f[2:5]])
    return out


def terms_of(group):
    """Sorted (type, atoms...) of an MDAnalysis TopologyGroup, types as molscope writes
    them (a bond's atoms ascending)."""
    return sorted((str(t.type),) + tuple(int(i) for i in t.indices) for t in group)


def check_data(mda, np, name, ours, u):
    a = u.atoms
    report(ours["natoms"] == a.n_atoms, "%s: atom count" % name,
           "%d vs %d" % (ours["natoms"], a.n_atoms))
    ty = [x[0] for x in ours["atoms"]]
    report(ty == list(a.types), "%s: atom types" % name, "first: %s vs %s" % (ty[:5], a.types[:5]))
    for k, attr in ((2, "charges"), (3, "masses")):
        if not hasattr(a, attr):
            continue
        v = np.array([x[k] for x in ours["atoms"]])
        d = float(np.abs(v - getattr(a, attr)).max())
        report(d < 1e-4, "%s: %s" % (name, attr), "largest difference %g" % d)
    resid = [x[1] for x in ours["atoms"]]
    report(resid == [int(r) for r in a.resids] or not hasattr(a, "charges"),
           "%s: molecule ids" % name, "%s vs %s" % (resid[:5], list(a.resids[:5])))
    bonds = sorted((str(t), i, j) for i, j, t in
                   ((min(b[0], b[1]), max(b[0], b[1]), b[2]) for b in ours["bond"]))
    ref = sorted((str(b.type), int(min(b.indices)), int(max(b.indices))) for b in u.bonds)
    report(bonds == ref, "%s: %d bonds with their types" % (name, len(ref)),
           "%d vs %d bonds" % (len(bonds), len(ref)))
    for kind, attr in (("angle", "angles"), ("dihedral", "dihedrals"), ("improper", "impropers")):
        if not hasattr(u, attr):
            continue
        ref = terms_of(getattr(u, attr))
        report(sorted(ours[kind]) == ref, "%s: %d %s with their types" % (name, len(ref), attr),
               "%d vs %d" % (len(ours[kind]), len(ref)))
    check_frames(np, name, ours, u)


def dump_origins(path):
    """xlo ylo zlo of every frame of a dump (from BOX BOUNDS, tilted boxes included)."""
    out = []
    with open(path) as f:
        lines = f.read().splitlines()
    for k, line in enumerate(lines):
        if line.startswith("ITEM: BOX BOUNDS"):
            rows = [[float(x) for x in lines[k + 1 + d].split()] for d in range(3)]
            xy, xz, yz = (rows[0][2], rows[1][2], rows[2][2]) if "xy" in line else (0, 0, 0)
            out.append([rows[0][0] - min(0.0, xy, xz, xy + xz), rows[1][0] - min(0.0, yz),
                        rows[2][0]])
    return out


def check_frames(np, name, ours, u, origins=None):
    worst, wbox = 0.0, 0.0
    for f, ts in enumerate(u.trajectory):
        shift = np.array(origins[f]) if origins else 0.0
        worst = max(worst, float(np.abs(np.array(ours["xyz"][f]) - shift - ts.positions).max()))
        wbox = max(wbox, float(np.abs(np.array(ours["cells"][f]) - ts.dimensions).max()))
    n = len(u.trajectory)
    report(len(ours["xyz"]) == n, "%s: %d frames" % (name, n), "%d vs %d" % (len(ours["xyz"]), n))
    report(worst < TOL, "%s: coordinates of every frame within 1e-3 A" % name,
           "largest difference %g" % worst)
    report(wbox < 1e-3, "%s: boxes (a b c alpha beta gamma)" % name,
           "largest difference %g" % wbox)


def main():
    try:
        warnings.filterwarnings("ignore")
        import numpy as np
        import MDAnalysis as mda
    except ImportError as e:
        R.skip("MDAnalysis", "not installed (%s)" % e)
        return 0
    data = os.environ.get("MS_TEST_DATA", os.path.join(os.path.dirname(__file__), "..", "data"))
    out = os.environ.get("MS_TEST_OUT", tempfile.gettempdir())
    p = lambda f: os.path.join(data, f)  # noqa: E731
    hd = p("helix.data")
    try:
        ours = molscope([("lammpsdata", hd)] +
                        [("lammpstrj", p("helix_%s.lammpstrj" % k))
                         for k in ("x", "xs", "xu", "xsu", "ortho")])
    except RuntimeError as e:
        report(False, "molscope reads the LAMMPS files", str(e))
        return 1
    check_data(mda, np, "helix.data", ours[0], mda.Universe(hd, atom_style="id resid type charge x y z"))
    dump = lambda k, **kw: mda.Universe(  # noqa: E731
        hd, p("helix_%s.lammpstrj" % k), format="LAMMPSDUMP",
        atom_style="id resid type charge x y z", **kw)
    xu = dump("xu", lammps_coordinate_convention="unwrapped")
    for n, k in enumerate(("x", "xs", "xu", "xsu")):
        check_frames(np, "helix_%s.lammpstrj (MDAnalysis: helix_xu)" % k, ours[1 + n], xu,
                     dump_origins(p("helix_%s.lammpstrj" % k)))
    ortho = dump("ortho", lammps_coordinate_convention="unscaled", unwrap_images=True)
    check_frames(np, "helix_ortho.lammpstrj, image flags", ours[5], ortho,
                 dump_origins(p("helix_ortho.lammpstrj")))
    for style, mda_style in (("full", "id resid type charge x y z"), ("atomic", "id type x y z")):
        path = os.path.join(out, "lammps_written_%s.data" % style)
        try:
            molscope([("write", "%s,%s,%s" % (hd, path, style))])
            mine = molscope([("lammpsdata", path)])[0]
            u = mda.Universe(path, atom_style=mda_style)
        except Exception as e:  # noqa: BLE001 - report any failure of either side
            report(False, "writelammpsdata %s read by MDAnalysis" % style, str(e)[-300:])
            continue
        check_data(mda, np, "writelammpsdata %s read by MDAnalysis" % style, mine, u)
    return 1 if R.failures else 0


if __name__ == "__main__":
    sys.exit(main())
