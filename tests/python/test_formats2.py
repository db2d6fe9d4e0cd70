#!/usr/bin/python3
"""test_formats2.py: the second set of readers and writers against independent programs.
tests/tools/msdump loads files as `mol new` + `mol addfile` do and prints what it read.
- MDAnalysis (python3-mdanalysis) writes XTC and TRR files of helix.psf + helix.dcd; msdump
  must read the XTC coordinates bit for bit as MDAnalysis reads them back, the TRR ones
  within 1e-5 A; MDAnalysis reads the PQR of APBS and PyMOL's MOL2 like msdump; msdump's
  TRR, XTC, PQR and MOL2 writers are read back by MDAnalysis (an MDAnalysis XTC written
  back by msdump reads identically).
- gemmi (Debian's gemmi) converts 1tii.pdb to mmCIF: msdump reads it like the PDB (names,
  residues, resids, chains, coordinates); gemmi builds assembly 1 of 3jqh.cif and of
  1a8o.pdb (REMARK 350): msdump's `assembly 1` has the same atoms at the same places.
- gridData (MDAnalysis' GridDataFormats) reads msdump's OpenDX of the cube seed grid, and
  msdump reads a CCP4 map gemmi writes (`gemmi mask` of 3jqh.cif) as gridData reads it.
Prints PASS:/FAIL:/SKIP: lines; SKIP when a peer is missing."""
import os
import shutil
import subprocess
import sys

import mstest

R = mstest.Reporter("formats2")
report = R.report
msdump = mstest.msdump


def run(exe, args):
    r = subprocess.run([exe] + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr.strip())


def trajectories(mda, np, exe, p, tmp):
    src = mda.Universe(p("helix.psf"), p("helix.dcd"))
    for ext in ("xtc", "trr"):
        path = tmp("mda.%s" % ext)
        with mda.Writer(path, src.atoms.n_atoms) as w:
            for ts in src.trajectory:
                w.write(src.atoms)
        u = mda.Universe(p("helix.psf"), path)
        ref = np.array([ts.positions.copy() for ts in u.trajectory], dtype=np.float32)
        try:
            ours = np.array(msdump(exe, [p("helix.psf"), path])["xyz"], dtype=np.float32)
        except RuntimeError as e:
            report(False, "%s: msdump reads MDAnalysis' file" % ext, str(e))
            continue
        same = ours.shape == ref.shape
        if ext == "xtc":
            report(same and bool((ours == ref).all()),
                   "XTC written by MDAnalysis: every coordinate of 10 frames equal to the bit",
                   "shapes %s %s, largest difference %s" % (
                       ours.shape, ref.shape, np.abs(ours - ref).max() if same else "-"))
        else:
            report(same and float(np.abs(ours - ref).max()) < 1e-5,
                   "TRR written by MDAnalysis: coordinates within 1e-5 A",
                   "largest difference %s" % (np.abs(ours - ref).max() if same else ours.shape))
    large_xtc(mda, np, exe, p, tmp)
    our_xtc(mda, np, exe, p, tmp)
    our_xtc_edges(mda, np, exe, tmp)
    # Our TRR writer, read back by MDAnalysis.
    out = tmp("ours.trr")
    run(exe, ["-o", out, p("helix.psf"), p("helix.dcd")])
    u = mda.Universe(p("helix.psf"), out)
    worst = max(float(np.abs(a.positions - b.positions).max()) for a, b in
                zip((src.trajectory[k] or src.atoms for k in range(10)),
                    (u.trajectory[k] or u.atoms for k in range(10))))
    report(len(u.trajectory) == 10 and worst < 1e-4,
           "msdump's TRR read by MDAnalysis: 10 frames within 1e-4 A", "worst %g" % worst)


def large_xtc(mda, np, exe, p, tmp):
    """A system large enough for frames to be decoded ahead on worker threads (1tii
    replicated to 12000 atoms, 7 frames moved and jittered differently): every frame equal
    to the bit with three threads and with one, and every second frame with step 2."""
    pdb, xtc = tmp("big.pdb"), tmp("big.xtc")
    rep = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "bench",
                       "replicate.py")
    subprocess.run([sys.executable, rep, p("1tii.pdb"), "12000", pdb], check=True,
                   capture_output=True)
    u = mda.Universe(pdb)
    rng = np.random.default_rng(7)
    base = u.atoms.positions.copy()
    with mda.Writer(xtc, u.atoms.n_atoms) as w:
        for k in range(7):
            u.atoms.positions = base + 0.37 * k + rng.normal(0, 0.1 * k, base.shape)
            w.write(u.atoms)
    ref = np.array([ts.positions.copy() for ts in mda.Universe(pdb, xtc).trajectory],
                   dtype=np.float32)
    for threads, step in (("3", 1), ("1", 1), ("3", 2)):
        env = dict(os.environ)
        env["MOLSCOPE_THREADS"] = threads
        name = "XTC of %d atoms, %s thread(s), step %d%s" % (
            u.atoms.n_atoms, threads, step,
            " (frames decoded ahead)" if threads != "1" and step == 1 else "")
        out = subprocess.run([exe, pdb, "-s", str(step), xtc], capture_output=True, text=True,
                             env=env)
        if out.returncode != 0:
            report(False, name, out.stderr.strip())
            continue
        xyz = {}
        for line in out.stdout.splitlines():
            if line.startswith("xyz\t"):
                f = line.split("\t")
                xyz.setdefault(int(f[1]), []).append([float(x) for x in f[3:6]])
        ours = np.array([xyz[k] for k in sorted(xyz)][1:], dtype=np.float32)
        want = ref[::step]
        same = ours.shape == want.shape
        report(same and bool((ours == want).all()), name + ": every coordinate equal to the bit",
               "shapes %s %s, largest difference %s" % (
                   ours.shape, want.shape, np.abs(ours - want).max() if same else "-"))


def our_xtc(mda, np, exe, p, tmp):
    """msdump's XTC writer read by MDAnalysis: helix.psf + helix.dcd written as XTC gives
    MDAnalysis every coordinate at the file's precision (the DCD's coordinate rounded to
    0.01 A, half away from zero, within float rounding) and the same boxes; MDAnalysis' own
    XTC files (helix and the replicated 1tii of large_xtc) read and written back by msdump
    read identically in MDAnalysis: coordinates and times to the bit, boxes to float
    rounding (the cell a b c alpha beta gamma between box and box is not exact)."""
    src = mda.Universe(p("helix.psf"), p("helix.dcd"))
    out = tmp("ours.xtc")
    run(exe, ["-o", out, p("helix.psf"), p("helix.dcd")])
    u = mda.Universe(p("helix.psf"), out)
    worst = worst_box = worst_round = 0.0
    for a, b in zip(src.trajectory, u.trajectory):
        x, y = src.atoms.positions.astype(np.float64), u.atoms.positions.astype(np.float64)
        worst = max(worst, float(np.abs(x - y).max()))
        k = np.sign(x * 100) * np.floor(np.abs(x * 100) + 0.5)
        worst_round = max(worst_round, float(np.abs(k / 100 - y).max()))
        worst_box = max(worst_box, float(np.abs(a.dimensions - b.dimensions).max()))
    report(len(u.trajectory) == 10 and worst <= 0.00501 and worst_round < 2e-5,
           "msdump's XTC read by MDAnalysis: 10 frames, coordinates within 0.005 A, each the "
           "DCD's rounded to 0.01 A", "worst %g, from the rounded %g" % (worst, worst_round))
    report(worst_box < 1e-4, "msdump's XTC read by MDAnalysis: the triclinic boxes",
           "worst %g" % worst_box)
    size, theirs = os.path.getsize(out), os.path.getsize(tmp("mda.xtc"))
    report(size <= 1.1 * theirs, "msdump's XTC compresses like MDAnalysis' (%d bytes, "
           "MDAnalysis %d)" % (size, theirs), "more than 10%% larger")
    # The PDB's own coordinates are msdump's first frame: skip it.
    for top, xtc, name, skip in ((p("helix.psf"), tmp("mda.xtc"), "helix", 0),
                                 (tmp("big.pdb"), tmp("big.xtc"), "1tii replicated", 1)):
        back = tmp("back.xtc")
        run(exe, ["-o", back, top, xtc])
        a, b = mda.Universe(top, xtc), mda.Universe(top, back)
        same = len(a.trajectory) + skip == len(b.trajectory)
        for fa, fb in zip(a.trajectory, b.trajectory[skip:]):
            same = same and bool((a.atoms.positions == b.atoms.positions).all()) and \
                same_box(np, fa.dimensions, fb.dimensions) and fa.time == fb.time
        report(same, "MDAnalysis' XTC (%s) written back by msdump reads identically in "
               "MDAnalysis: coordinates and times to the bit, boxes within 1e-6" % name,
               "differs")


def our_xtc_edges(mda, np, exe, tmp):
    """msdump's XTC of coordinates that take the format's rarer paths, read by MDAnalysis
    (whose decoder is GROMACS' xdrfile): ranges past 2^24 integers (separate bit fields), a
    walk of 20000 A steps (small differences of more than 64 bits), 5 atoms (plain floats).
    Coordinates come from XYZ files written here; MDAnalysis must read each as the integer
    x * 100 rounded half away from zero, made a float as GROMACS' reader does, to the bit
    (plain floats within 1e-5 A)."""
    rng = np.random.default_rng(11)
    n = 3000
    far = rng.uniform(-1e6, 1e6, (n, 3))
    far[1:][np.arange(1, n) % 5 != 0] = 0
    far = np.cumsum(far, axis=0) % 2e6 - 1e6 + rng.uniform(-0.6, 0.6, (n, 3))
    walk = np.cumsum(rng.uniform(-20000, 20000, (n, 3)), axis=0)
    for name, xyz in (("ranges past 2^24 integers", far), ("20000 A steps", walk),
                      ("5 atoms", rng.uniform(-30, 30, (5, 3)))):
        src, out = tmp("edge.xyz"), tmp("edge.xtc")
        with open(src, "w") as f:
            f.write("%d\nedge\n" % len(xyz))
            for x, y, z in xyz:
                f.write("C %.4f %.4f %.4f\n" % (x, y, z))
        run(exe, ["-o", out, src])
        x = np.loadtxt(src, skiprows=2, usecols=(1, 2, 3)).astype(np.float32).astype(np.float64)
        got = mda.Universe(src, out).atoms.positions.astype(np.float64)
        if len(xyz) > 9:
            # The integer, then as GROMACS' reader makes floats of it: k * (1/1000) * 10.
            k = (np.sign(x * 100) * np.floor(np.abs(x * 100) + 0.5)).astype(np.float32)
            want = (k * np.float32(0.001)) * np.float32(10)
            worst = float(np.abs(want - got).max())
            ok = worst == 0
        else:
            worst = float(np.abs(x - got).max())
            ok = worst < 1e-5
        report(ok, "msdump's XTC (%s) read by MDAnalysis at the file's precision" % name,
               "worst %g" % worst)


def same_box(np, a, b):
    """Both without a box, or the same box within float rounding."""
    if a is None or b is None:
        return a is None and b is None
    return bool(np.allclose(a, b, rtol=1e-6, atol=0))


def same_atoms(name, ours, u, np, names=True, tol=1e-3):
    n = u.atoms.n_atoms
    ok = ours["natoms"] == n
    report(ok, "%s: %d atoms" % (name, n), "msdump has %d" % ours["natoms"])
    if not ok:
        return
    if names:
        bad = [i for i, a in enumerate(ours["atoms"])
               if a[0] != u.atoms.names[i] or a[1] != u.atoms.resnames[i]
               or a[2] != u.atoms.resids[i]]
        report(not bad, "%s: names, residue names and resids" % name,
               "atom %d: %s" % (bad[0], ours["atoms"][bad[0]]) if bad else "")
    d = float(np.abs(np.array(ours["xyz"][0]) - u.atoms.positions).max())
    report(d <= tol, "%s: coordinates within %g A" % (name, tol), "largest difference %g" % d)


def small_formats(mda, np, exe, p, tmp):
    pqr = "/usr/share/apbs/examples/pbam/1a63.pqr"
    mol2 = p("small03_1.mol2")
    for name, path in (("APBS 1a63.pqr", pqr), ("PyMOL small03.mol2 (first molecule)", mol2)):
        if not os.path.exists(path):
            print("SKIP: %s: %s: %s is missing" % (R.suite, name, path))
            continue
        u = mda.Universe(path)
        ours = msdump(exe, [path])
        same_atoms(name, ours, u, np)
        if path == pqr:
            bad = [i for i in range(u.atoms.n_atoms) if ours["natoms"] != u.atoms.n_atoms]
            report(not bad, "%s: read" % name)
        if path == mol2:
            bonds = sorted(tuple(sorted(b)) for b in u.bonds.indices.tolist())
            report(len(bonds) == 9, "small03 first molecule: MDAnalysis sees 9 bonds")
    for ext in ("pqr", "mol2"):
        out = tmp("ours.%s" % ext)
        run(exe, ["-o", out, p("pept.pdb")])
        ours = msdump(exe, [p("pept.pdb")])
        same_atoms("msdump's %s of pept.pdb read by MDAnalysis" % ext.upper(), ours,
                   mda.Universe(out), np)


def with_gemmi(np, exe, p, tmp):
    if not shutil.which("gemmi"):
        print("SKIP: %s: gemmi: the gemmi program is not installed" % R.suite)
        return
    cif = tmp("1tii.cif")
    subprocess.run(["gemmi", "convert", p("1tii.pdb"), cif], check=True, capture_output=True)
    a, b = msdump(exe, [p("1tii.pdb")]), msdump(exe, [cif])
    report(a["natoms"] == b["natoms"], "gemmi's mmCIF of 1tii: %d atoms" % a["natoms"],
           "%d" % b["natoms"])
    if a["natoms"] == b["natoms"]:
        bad = [i for i in range(a["natoms"]) if a["atoms"][i][0] != b["atoms"][i][0] or
               a["atoms"][i][1:3] != b["atoms"][i][1:3] or a["atoms"][i][4] != b["atoms"][i][4]]
        report(not bad, "gemmi's mmCIF of 1tii: names, residue names, resids and chains as the "
               "PDB", "atom %d: %s vs %s" % (bad[0], a["atoms"][bad[0]], b["atoms"][bad[0]])
               if bad else "")
        d = float(np.abs(np.array(a["xyz"][0]) - np.array(b["xyz"][0])).max())
        report(d < 1e-4, "gemmi's mmCIF of 1tii: coordinates as the PDB", "%g" % d)
    for src in ("3jqh.cif", "1a8o.pdb"):
        ref = tmp("asm_" + src.replace(".", "_") + ".pdb")
        subprocess.run(["gemmi", "convert", "--assembly=1", p(src), ref], check=True,
                       capture_output=True)
        g = msdump(exe, [ref])
        try:
            ours = msdump(exe, ["-a", "1", p(src)])
        except RuntimeError as e:
            report(False, "%s assembly 1: msdump builds it" % src, str(e))
            continue
        base = msdump(exe, [p(src)])
        copies = ours["natoms"] // max(1, base["natoms"])
        report(ours["natoms"] == g["natoms"],
               "%s assembly 1: %d atoms (%d copies of %d), as gemmi builds it" % (
                   src, g["natoms"], copies, base["natoms"]), "msdump has %d" % ours["natoms"])
        if ours["natoms"] == g["natoms"]:
            from scipy.spatial import cKDTree
            x, y = np.array(ours["xyz"][0]), np.array(g["xyz"][0])
            # Match atoms by position (gemmi may order the copies differently): every atom
            # of each must have one of the other's within the tolerance.
            d = max(float(cKDTree(y).query(x)[0].max()), float(cKDTree(x).query(y)[0].max()))
            report(d < 2e-3, "%s assembly 1: every atom where gemmi puts it" % src,
                   "largest difference %g" % d)


def grids(np, exe, p, tmp):
    try:
        import gridData
    except ImportError:
        print("SKIP: %s: gridData: python3-griddataformats is not installed" % R.suite)
        return
    dx = tmp("ours.dx")
    run(exe, ["-o", dx, p("grid345.cube")])
    g = gridData.Grid(dx)
    i, j, k = np.meshgrid(np.arange(3), np.arange(4), np.arange(5), indexing="ij")
    report(g.grid.shape == (3, 4, 5) and bool((g.grid == i + 10 * j + 100 * k).all()),
           "msdump's DX of the cube test grid read by gridData: every value")
    report(np.allclose(g.origin, np.array([1, 2, 3]) * 0.529177210903, atol=1e-6) and
           np.allclose(g.delta, np.array([0.5, 1, 2]) * 0.529177210903, atol=1e-6),
           "msdump's DX: origin and spacing in Angstrom (Bohr converted)")
    if not shutil.which("gemmi"):
        return
    msk = tmp("3jqh.ccp4")
    subprocess.run(["gemmi", "mask", p("3jqh.cif"), msk], check=True,
                   capture_output=True)
    ref = gridData.Grid(msk)
    out = tmp("gemmi_mask.dx")
    run(exe, ["-o", out, msk])
    ours = gridData.Grid(out)
    report(ours.grid.shape == ref.grid.shape and bool((ours.grid == ref.grid).all()),
           "gemmi's CCP4 mask of 3jqh.cif: every value as gridData reads it (%s)" %
           "x".join(map(str, ref.grid.shape)))
    report(np.allclose(ours.delta, ref.delta, atol=1e-5),
           "gemmi's CCP4 mask: grid spacing as gridData reads it",
           "%s vs %s" % (ours.delta, ref.delta))


def main():
    mods = R.imports(["numpy", "MDAnalysis"], "python3-mdanalysis")
    if mods is None:
        return 0
    np, mda = mods
    srcdir, builddir, data, outdir = mstest.dirs()
    exe = R.msdump_exe(builddir)
    if exe is None:
        return 1
    corpus = os.path.join(srcdir, "tests", "fuzz", "corpus")
    seeds = {"small03_1.mol2": os.path.join(corpus, "mol2", "small03_1.mol2"),
             "grid345.cube": os.path.join(corpus, "cube", "grid345.cube")}
    p = lambda f: seeds.get(f, os.path.join(data, f))
    tmp = lambda f: os.path.join(outdir, "formats2_%d_%s" % (os.getpid(), f))
    return R.steps([lambda: trajectories(mda, np, exe, p, tmp),
                    lambda: small_formats(mda, np, exe, p, tmp),
                    lambda: with_gemmi(np, exe, p, tmp), lambda: grids(np, exe, p, tmp)])


if __name__ == "__main__":
    sys.exit(main())
