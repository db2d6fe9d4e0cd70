#!/usr/bin/python3
"""measure_refs.py: how the reference numbers in tests/unit/test_measure.c were obtained.

Run by hand with Debian's Python (/usr/bin/python3 tests/python/measure_refs.py); it is not
part of the suite. It computes every number independently of molscope: MDAnalysis reads the
PDB files, numpy does the arithmetic (plain formulas, brute force over all pairs), and
Biopython's Shrake-Rupley gives the surface areas. Masses and radii are the standard
values: C 12.011 N 14.007 O 15.999 S 32.06; Bondi radii C 1.70 N 1.55 O 1.52 S 1.80.
"""
import os
import sys
import warnings

import numpy as np

warnings.simplefilter("ignore")
import MDAnalysis as mda  # noqa: E402
from MDAnalysis.lib.distances import calc_angles, calc_bonds, calc_dihedrals  # noqa: E402

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
MASS = {"C": 12.011, "N": 14.007, "O": 15.999, "S": 32.06}
RADIUS = {"C": 1.70, "N": 1.55, "O": 1.52, "S": 1.80}


def kabsch_rmsd(x, y):
    """Best rotation RMSD (proper rotations only), by SVD."""
    xc, yc = x - x.mean(0), y - y.mean(0)
    u, s, vt = np.linalg.svd(xc.T @ yc)
    d = np.sign(np.linalg.det(u @ vt))
    r = (u @ np.diag([1, 1, d]) @ vt).T
    return np.sqrt((((xc @ r.T) - yc) ** 2).sum(1).mean())


def tii():
    u = mda.Universe(os.path.join(DATA, "1tii.pdb"))
    a = u.atoms
    x = a.positions.astype(np.float64)
    m = np.array([MASS[e] for e in a.elements])
    r = np.array([RADIUS[e] for e in a.elements])
    c = x.mean(0)
    cm = (m[:, None] * x).sum(0) / m.sum()
    print("1tii center", c)
    print("1tii mass center", cm)
    print("1tii rgyr", np.sqrt(((x - c) ** 2).sum(1).mean()))
    print("1tii mass rgyr", np.sqrt((m * ((x - cm) ** 2).sum(1)).sum() / m.sum()))
    print("1tii min", x.min(0), "max", x.max(0))
    print("1tii min-r", (x - r[:, None]).min(0), "max+r", (x + r[:, None]).max(0))
    d = x - cm
    t = np.zeros((3, 3))
    for i in range(3):
        for j in range(3):
            t[i, j] = -(m * d[:, i] * d[:, j]).sum()
    t += np.eye(3) * (m * (d ** 2).sum(1)).sum()
    print("1tii inertia moments", sorted(np.linalg.eigvalsh(t))[::-1])
    ca_d = u.select_atoms("chainID D and name CA").positions.astype(np.float64)
    ca_e = u.select_atoms("chainID E and name CA").positions.astype(np.float64)
    print("1tii CA D/E rmsd", np.sqrt(((ca_d - ca_e) ** 2).sum(1).mean()))
    print("1tii CA D/E fitted rmsd", kabsch_rmsd(ca_d, ca_e))
    dd = u.select_atoms("chainID D").positions.astype(np.float64)
    ee = u.select_atoms("chainID E").positions.astype(np.float64)
    print("1tii chain D/E fitted rmsd", kabsch_rmsd(dd, ee))
    dist = np.sqrt(((dd[:, None, :] - ee[None, :, :]) ** 2).sum(2))
    print("1tii D/E contacts <= 3.5", (dist <= 3.5).sum(), "<= 4.0", (dist <= 4.0).sum())
    ind = np.argwhere(dist <= 3.5)
    first_d = u.select_atoms("chainID D").indices
    first_e = u.select_atoms("chainID E").indices
    print("1tii D/E first contact pair", first_d[ind[0][0]], first_e[ind[0][1]])
    # contacts inside chain D: pairs within 3.0 A, not at the same place, not bonded (VMD's
    # distance rule d < 0.6 (r1 + r2) with the Bondi radii, plus the CONECT records)
    rd = np.array([RADIUS[e] for e in u.select_atoms("chainID D").elements])
    dd2 = np.sqrt(((dd[:, None, :] - dd[None, :, :]) ** 2).sum(2))
    bonded = dd2 < 0.6 * (rd[:, None] + rd[None, :])
    for line in open(os.path.join(DATA, "1tii.pdb")):
        if line.startswith("CONECT"):
            ser = [int(line[k:k + 5]) - 1 for k in range(6, 31, 5) if line[k:k + 5].strip()]
            for j in ser[1:]:
                if ser[0] < len(dd) and j < len(dd):
                    bonded[ser[0], j] = bonded[j, ser[0]] = True
    iu = np.triu_indices(len(dd), 1)
    dist, bond = dd2[iu], bonded[iu]
    print("1tii chain D contacts <= 3.0", ((dist <= 3.0) & (dist ** 2 >= 0.001) & ~bond).sum(),
          "bonded", bond.sum())


def sasa():
    from Bio.PDB import PDBParser
    from Bio.PDB.SASA import ShrakeRupley
    s = PDBParser(QUIET=True).get_structure("1tii", os.path.join(DATA, "1tii.pdb"))
    chain = s[0]["D"]
    ShrakeRupley(probe_radius=1.4, n_points=5000).compute(chain, level="C")
    print("1tii chain D SASA (Biopython Shrake-Rupley, 5000 points)", chain.sasa)


def pept():
    u = mda.Universe(os.path.join(DATA, "pept.pdb"))
    x = u.atoms.positions.astype(np.float64)
    # residue 1's N CA C and residue 2's N: atoms 0 1 6 8
    print("pept bond 0-1", calc_bonds(x[0], x[1]))
    print("pept angle 0-1-6", np.degrees(calc_angles(x[0], x[1], x[6])))
    print("pept dihedral 0-1-6-8", np.degrees(calc_dihedrals(x[0], x[1], x[6], x[8])))
    print("pept dihedral 6-8-9-12", np.degrees(calc_dihedrals(x[6], x[8], x[9], x[12])))
    print("names", list(u.atoms.names[:16]))


def gofr_water(rmax=9.0, bins=(25, 27, 28, 30, 45, 60, 89)):
    """O-O g(r) of water648.pdb in its cubic box, brute force with VMD's normalisation
    (minimum image; past half the box the shells lose the caps beyond the faces)."""
    u = mda.Universe(os.path.join(DATA, "water648.pdb"))
    o = u.select_atoms("name O").positions.astype(np.float64)
    L, delta = 18.774349, 0.1
    nbins = int(rmax / delta + 1.0)
    d = o[:, None, :] - o[None, :, :]
    d -= L * np.floor(d / L + 0.5)
    r = np.sqrt((d ** 2).sum(2))
    n = len(o)
    r = r[~np.eye(n, dtype=bool)]
    hmax = min(nbins, int(np.sqrt(0.5) * L / delta) + 1)
    hist = np.bincount((r / delta).astype(int), minlength=nbins + 200)[:hmax]
    rin, rout = delta * np.arange(hmax), delta * np.arange(1, hmax + 1)
    vol = 4 / 3 * np.pi * (rout ** 3 - rin ** 3)
    for rr, sgn in ((rout, -1), (rin, 1)):
        h = rr > L / 2
        cap = np.pi / 3 * (rr - L / 2) ** 2 * (2 * rr + L / 2)
        vol += sgn * 3 * 2 * np.where(h, cap, 0)
    g = hist * (L ** 3 / (n * n - n)) / vol
    print("water O-O nbins", nbins, "hmax", hmax, "pairs counted", hist.sum())
    for i in bins:
        print("water O-O bin", i, "hist", hist[i], "g", g[i], "numint", hist[:i + 1].sum() / n)


def hbonds_helix():
    """Hydrogen bonds D-H...A in helix_amber.pdb with VMD's criteria (3.0 A, 20 degrees)."""
    u = mda.Universe(os.path.join(DATA, "helix_amber.pdb"))
    names = u.atoms.names
    x = u.atoms.positions.astype(np.float64)
    isH = np.array([nm[0] == "H" or (nm[0].isdigit() and nm[1:2] == "H") for nm in names])
    rad = np.array([{"H": 1.0, "C": 1.5, "N": 1.4, "O": 1.3, "S": 1.9}.get(nm.lstrip("0123456789")[0], 1.5)
                    for nm in names])
    dist = np.sqrt(((x[:, None] - x[None]) ** 2).sum(2))
    bonded = (dist < 0.6 * (rad[:, None] + rad[None])) & ~(isH[:, None] & isH[None])
    np.fill_diagonal(bonded, False)
    found = []
    heavy = np.where(~isH)[0]
    for cut, ang in ((3.0, 20.0), (3.5, 30.0)):
        found = []
        for d in heavy:
            hs = [h for h in np.where(bonded[d])[0] if isH[h]]
            for a in heavy:
                if a == d or bonded[d, a] or dist[d, a] > cut:
                    continue
                for h in hs:
                    v1, v2 = x[h] - x[d], x[a] - x[h]
                    c = np.dot(v1, v2) / np.linalg.norm(v1) / np.linalg.norm(v2)
                    if np.degrees(np.arccos(np.clip(c, -1, 1))) < ang:
                        found.append((d, a, h))
        print("helix hbonds", cut, ang, len(found), sorted(found)[:3])


if __name__ == "__main__":
    for f in (tii, sasa, pept, gofr_water, lambda: gofr_water(15.0, (93, 100, 120, 132)),
              hbonds_helix):
        f()
        sys.stdout.flush()
