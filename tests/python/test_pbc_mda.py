#!/usr/bin/python3
"""test_pbc_mda.py: pbctools' `pbc wrap`, `pbc join` and `pbc unwrap` against MDAnalysis.

molscope loads a periodic trajectory, runs one pbc command over every frame and prints the
coordinates; MDAnalysis reads the same files with its own readers and applies its own
transformations: `wrap` (atoms, residues by centre of geometry) for `pbc wrap`, `unwrap`
(residues made whole through their bonds, reference None) for `pbc join`; `pbc unwrap` of
the wrapped water trajectory must give back the continuous one it was made from
(tests/data/make/make_pbc.py; MDAnalysis 2.4 has no NoJump transformation). Systems: 216
waters in a triclinic cell that changes per frame (water_tric.dcd), the same with a cubic
cell set by `pbc set`, and the triclinic helix.psf + helix.dcd. Positions must agree to
1e-3 A. Prints PASS:/FAIL:/SKIP: lines for tests/run-tests.

MDAnalysis 2.4's `wrap` (apply_PBC) is not the exact parallelepiped when both b_x and c_y
are non-zero (its one-box shift along a ignores their coupling: an atom at fractional
a -0.003 stays where it is), so its transformations are compared on cubic and monoclinic
(gamma 90) cells, and the fully triclinic cells with the exact wrap by fractional
coordinates, computed with MDAnalysis' transform_RtoS / transform_StoR."""
import os
import subprocess
import tempfile
import warnings

import mstest

R = mstest.Reporter("pbc_mda")
DATA = os.environ.get("MS_TEST_DATA", os.path.join(os.path.dirname(__file__), "..", "data"))
MOLSCOPE = os.environ.get("MOLSCOPE", "src/molscope")
TOL = 1e-3
WATER = ["spc216.gro", "water_tric.dcd"]
HELIX = ["helix.psf", "helix.dcd"]
CUBE = [18.62, 18.62, 18.62, 90.0, 90.0, 90.0]
MONO = [18.62, 19.0, 19.5, 80.0, 85.0, 90.0]

# name, files, the pbc command, the cell set by `pbc set` first (None: the file's), and
# what it is compared with: MDAnalysis' transformations (mda_*), the exact wrap by
# fractional coordinates through MDAnalysis' transform_RtoS/StoR (exact_*), or the
# continuous trajectory (cont).
CASES = [
    ("wrap atoms, cubic water", WATER, "pbc wrap -all", CUBE, "mda_wrap_atoms"),
    ("wrap atoms, monoclinic water", WATER, "pbc wrap -all", MONO, "mda_wrap_atoms"),
    ("wrap -compound residue, monoclinic water", WATER, "pbc wrap -all -compound residue", MONO,
     "mda_wrap_res"),
    ("wrap -center origin, monoclinic water", WATER, "pbc wrap -all -center origin", MONO,
     "mda_wrap_origin"),
    ("wrap atoms, triclinic water", WATER, "pbc wrap -all", None, "exact_atoms"),
    ("wrap -compound residue, triclinic water", WATER, "pbc wrap -all -compound residue", None,
     "exact_res"),
    ("wrap -compound residue, triclinic helix", HELIX, "pbc wrap -all -compound res", None,
     "exact_res"),
    ("join residue, triclinic water", WATER, "pbc join residue -all", None, "mda_unwrap_res"),
    ("join residue -bondlist, triclinic water", WATER, "pbc join residue -all -bondlist", None,
     "mda_unwrap_res"),
    ("wrap, then join connected -bondlist, triclinic helix", HELIX,
     "pbc wrap -all; pbc join connected -bondlist -all", None, "exact_atoms+mda_unwrap_frag"),
    ("unwrap, triclinic water", WATER, "pbc unwrap", None, "cont"),
]

SCRIPT = r"""
set out [open {%(out)s} w]
foreach {name files cmd cell} {%(cases)s} {
    set m [mol new [file join {%(data)s} [lindex $files 0]] waitfor all]
    if {[string match *.gro [lindex $files 0]]} { animate delete beg 0 end 0 $m }
    mol addfile [file join {%(data)s} [lindex $files 1]] waitfor all $m
    if {[llength $cell]} { pbc set $cell -all }
    eval $cmd
    set all [atomselect $m all]
    for {set f 0} {$f < [molinfo $m get numframes]} {incr f} {
        $all frame $f
        puts $out "$name|$f|[join [$all get {x y z}]]"
    }
    $all delete
    mol delete $m
}
close $out
quit
"""


def molscope_coords():
    with tempfile.TemporaryDirectory() as tmp:
        out, script = os.path.join(tmp, "coords.txt"), os.path.join(tmp, "run.tcl")
        cases = " ".join("{%s} {%s} {%s} {%s}" % (n, " ".join(f), c, " ".join(map(str, cell or [])))
                         for n, f, c, cell, _ in CASES)
        with open(script, "w") as f:
            f.write(SCRIPT % {"out": out, "cases": cases, "data": DATA})
        run = subprocess.run([MOLSCOPE, "-dispdev", "text", "-e", script], stdin=subprocess.DEVNULL,
                             capture_output=True, text=True, timeout=300)
        if not os.path.exists(out):
            raise RuntimeError(run.stdout[-500:] + run.stderr[-500:])
        coords = {}
        with open(out) as f:
            for line in f:
                name, frame, xyz = line.rstrip("\n").split("|")
                coords.setdefault(name, []).append([float(v) for v in xyz.split()])
        return coords


def universe(mda, files, cell):
    u = mda.Universe(*[os.path.join(DATA, f) for f in files], guess_bonds=files == WATER)
    if cell:
        from MDAnalysis.transformations import boxdimensions
        u.trajectory.add_transformations(boxdimensions.set_dimensions(cell))
    return u


def exact_wrap(points, dims):
    """Points moved into the parallelepiped: fractional coordinates in [0, 1)."""
    import numpy as np
    from MDAnalysis.lib.distances import transform_RtoS, transform_StoR
    s = transform_RtoS(np.asarray(points, dtype=np.float64), dims)
    return transform_StoR(s - np.floor(s), dims)


def reference(ag, ts, how):
    """Apply the comparison's transformation to ag in frame ts."""
    if how == "mda_wrap_atoms":
        ag.wrap(compound="atoms")
    elif how == "mda_wrap_res":
        ag.wrap(compound="residues", center="cog")
    elif how == "mda_wrap_origin":
        half = 0.5 * ts.triclinic_dimensions.sum(axis=0)
        ag.translate(half)
        ag.wrap(compound="atoms")
        ag.translate(-half)
    elif how == "exact_atoms":
        ag.positions = exact_wrap(ag.positions, ts.dimensions)
    elif how == "exact_res":
        centers = ag.center_of_geometry(compound="residues")
        shift = exact_wrap(centers, ts.dimensions) - centers
        ag.positions = ag.positions + shift[ag.resindices]
    elif how == "mda_unwrap_res":
        ag.unwrap(compound="residues", reference=None)
    else:
        ag.unwrap(compound="fragments", reference=None)


def expected(mda, files, cell, how):
    """The comparison's positions, frame by frame."""
    import numpy as np
    if how == "cont":
        u = mda.Universe(os.path.join(DATA, "spc216.gro"), os.path.join(DATA, "water_tric_cont.dcd"))
        return [u.atoms.positions.copy() for _ in u.trajectory]
    u = universe(mda, files, cell)
    out = []
    for ts in u.trajectory:
        for step in how.split("+"):
            reference(u.atoms, ts, step)
        out.append(np.array(u.atoms.positions, dtype=np.float64))
    return out


def main():
    try:
        warnings.simplefilter("ignore")
        import numpy as np
        import MDAnalysis as mda
    except ImportError:
        R.skip("all", "python3-mdanalysis is not installed")
        return 0
    try:
        ours = molscope_coords()
    except (RuntimeError, subprocess.TimeoutExpired) as e:
        R.report(False, "molscope runs the pbc commands", str(e))
        return 1
    for name, files, cmd, cell, how in CASES:
        want = expected(mda, files, cell, how)
        got = ours.get(name)
        if got is None or len(got) != len(want):
            R.report(False, name, "molscope gave %s frames, MDAnalysis %d" %
                     (None if got is None else len(got)), len(want))
            continue
        worst = max(float(np.abs(np.array(g).reshape(-1, 3) - w).max()) for g, w in zip(got, want))
        u = universe(mda, files, None)
        moved = max(float(np.abs(np.array(g).reshape(-1, 3) - u.atoms.positions).max())
                    for g, _ in zip(got, u.trajectory))
        R.report(moved > 1.0, "%s: the command moved atoms (so the comparison means something)" % name,
                 "largest move %g A" % moved)
        R.report(worst <= TOL, "%s (%s): positions of %d frames within %g A" % (name, cmd, len(want), TOL),
                 "largest difference %g A" % worst)
    return 1 if R.failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
