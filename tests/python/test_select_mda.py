#!/usr/bin/python3
"""test_select_mda.py: molscope's atom selections against MDAnalysis selections with the same
meaning (name, resname, resid, around, byres) on real structures. An atom on which the two
disagree only counts as a failure when its distance is not within 1e-3 A of the cutoff
(float rounding may put such an atom on either side). Prints PASS:/FAIL:/SKIP: lines."""
import os
import subprocess
import sys
import tempfile
import warnings

warnings.filterwarnings("ignore")
try:
    import numpy as np
    import MDAnalysis as mda
    from MDAnalysis.lib.distances import distance_array
except ImportError as e:
    print("SKIP: select_mda: MDAnalysis is not available (%s)" % e)
    sys.exit(0)

DATA = os.environ.get("MS_TEST_DATA", "tests/data")
MOLSCOPE = os.environ.get("MOLSCOPE", "src/molscope")

# (molscope selection, MDAnalysis selection, cutoff and reference for near-boundary atoms)
CASES = {
    "1tii.pdb": [
        ("name CA", "name CA", None),
        ("resname HOH", "resname HOH", None),
        ("resid 10 to 50", "resid 10:50", None),
        ("name \"C.*\" and resname LYS ARG", "name C* and resname LYS ARG", None),
        ("exwithin 5 of resname HOH", "around 5 resname HOH", (5, "resname HOH")),
        ("within 4 of (resid 10 and chain A)",
         "(around 4 (resid 10 and chainID A)) or (resid 10 and chainID A)",
         (4, "resid 10 and chainID A")),
        ("same residue as (exwithin 3.5 of resname HOH)", "byres (around 3.5 resname HOH)",
         None),
        ("exwithin 7.25 of (name SG and chain D)", "around 7.25 (name SG and chainID D)",
         (7.25, "name SG and chainID D")),
    ],
    "il2.pdb": [
        ("name CA CB", "name CA CB", None),
        ("resname LEU ILE", "resname LEU ILE", None),
        ("resid 20 to 40 and not name \"H.*\"", "resid 20:40 and not name H*", None),
        ("exwithin 6 of resid 30", "around 6 resid 30", (6, "resid 30")),
        ("same residue as (exwithin 5 of resname TRP)", "byres (around 5 resname TRP)", None),
    ],
}


def molscope_indices(path, sels):
    """Run molscope once on a file; one list of indices per selection."""
    with tempfile.NamedTemporaryFile("w", suffix=".tcl", delete=False) as f:
        f.write("mol new {%s} waitfor all\n" % path)
        for s in sels:
            f.write("puts \"SEL [[atomselect top {%s}] list]\"\n" % s)
        f.write("quit\n")
        script = f.name
    try:
        out = subprocess.run([MOLSCOPE, "-dispdev", "text", "-e", script],
                             stdin=subprocess.DEVNULL, capture_output=True, text=True,
                             timeout=120)
    finally:
        os.unlink(script)
    lines = [l for l in out.stdout.splitlines() if l.startswith("SEL")]
    if out.returncode != 0 or len(lines) != len(sels):
        raise RuntimeError("molscope failed: %s %s" % (out.stdout[-500:], out.stderr[-500:]))
    return [set(int(x) for x in l.split()[1:]) for l in lines]


def boundary_only(u, diff, near):
    """Are all the differing atoms within 1e-3 A of the cutoff from the reference?"""
    if not diff:
        return True
    if near is None:
        return False
    cutoff, ref = near
    d = distance_array(u.atoms[sorted(diff)].positions, u.select_atoms(ref).positions)
    return bool(np.all(np.abs(d.min(axis=1) - cutoff) < 1e-3))


def main():
    failures = 0
    for name, cases in CASES.items():
        path = os.path.join(DATA, name)
        u = mda.Universe(path)
        got = molscope_indices(path, [c[0] for c in cases])
        for (ms_sel, mda_sel, near), ms_set in zip(cases, got):
            ref = set(u.select_atoms(mda_sel).indices.tolist())
            diff = ms_set ^ ref
            label = "select_mda: %s: '%s' = MDAnalysis '%s'" % (name, ms_sel, mda_sel)
            if not ref:
                print("FAIL: %s: MDAnalysis selects nothing (a vacuous check)" % label)
                failures += 1
            elif boundary_only(u, diff, near):
                print("PASS: %s (%d atoms%s)" % (label, len(ref),
                                                 ", %d on the boundary" % len(diff) if diff else ""))
            else:
                print("FAIL: %s: molscope %d atoms, MDAnalysis %d, %d differ (e.g. %s)"
                      % (label, len(ms_set), len(ref), len(diff), sorted(diff)[:5]))
                failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
