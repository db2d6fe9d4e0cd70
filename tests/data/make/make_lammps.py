#!/usr/bin/python3
"""make_lammps.py: the LAMMPS test files of tests/data, made from helix.psf + helix.dcd.

- helix.data: MDAnalysis' DATAWriter (atom style full) of frame 0 with atom types numbered
  by element (H 1, C 2, N 3, O 4, S 5), the PSF's bonds, the angles and dihedrals
  MDAnalysis guesses from them, one improper per atom with three bonds (centre first),
  every term typed by its sorted atom types, charges and masses from the PSF, and a
  triclinic box (40 42 44, 80 85 95 degrees).
- helix_*.lammpstrj: LAMMPS text dumps of the 10 frames of helix.dcd written here (MDAnalysis
  has no dump writer) in that box, atoms listed in a shuffled order (a different one each
  frame): helix_x.lammpstrj wrapped x y z with image flags ix iy iz, helix_xs scaled xs ys
  zs with image flags, helix_xu unwrapped xu yu zu, helix_xsu scaled unwrapped; the columns
  come in a different order in each file. Wrapping and scaling use LAMMPS' own formulas.
  helix_ortho.lammpstrj: the first 3 frames wrapped with image flags in an orthogonal box
  (24 26 28), where MDAnalysis 2.4.2's image unwrapping (box lengths only) applies.
Run with /usr/bin/python3 from this folder; writes into tests/data."""
import os
import warnings

import numpy as np

warnings.filterwarnings("ignore")
import MDAnalysis as mda  # noqa: E402
from MDAnalysis.topology import guessers  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
BOX = [40.0, 42.0, 44.0, 80.0, 85.0, 95.0]
ELEMENT_TYPE = {"H": "1", "C": "2", "N": "3", "O": "4", "S": "5"}


def typed(groups, types):
    """Term index tuples (each once, either direction) and a numeric type per term (the
    rank of its canonical type tuple)."""
    seen = set()
    groups = [g for g in groups
              if min(tuple(g), tuple(g)[::-1]) not in seen and
              not seen.add(min(tuple(g), tuple(g)[::-1]))]
    keys = []
    for g in groups:
        t = tuple(types[i] for i in g)
        keys.append(min(t, t[::-1]))
    ranks = {k: str(n + 1) for n, k in enumerate(sorted(set(keys)))}
    return [tuple(int(i) for i in g) for g in groups], [ranks[k] for k in keys]


def impropers(u):
    out = []
    for a in u.atoms:
        nb = sorted(b.index for b in a.bonded_atoms)
        if len(nb) == 3:
            out.append((a.index, nb[0], nb[1], nb[2]))
    return out


def make_data(u):
    elem = [n[0] for n in u.atoms.names]
    u.atoms.types = [ELEMENT_TYPE[e] for e in elem]
    types = list(u.atoms.types)
    bonds = [tuple(b.indices) for b in u.bonds]
    angles = [tuple(a) for a in guessers.guess_angles(u.bonds)]
    u.delete_bonds(list(u.bonds))
    vals, tys = typed(bonds, types)
    u.add_bonds(vals, types=tys)
    vals, tys = typed(angles, types)
    u.add_angles(vals, types=tys)
    dih = [tuple(d) for d in guessers.guess_dihedrals(u.angles)]
    vals, tys = typed(dih, types)
    u.add_dihedrals(vals, types=tys)
    vals, tys = typed(impropers(u), types)
    u.add_impropers(vals, types=tys)
    u.dimensions = BOX
    path = os.path.join(DATA, "helix.data")
    u.atoms.write(path)
    fix_type_counts(path, u)


def fix_type_counts(path, u):
    """MDAnalysis 2.4.2 counts term types with TopologyGroup.types(), which takes a type
    string and its reversal for one type ("12" and "21"): its "N dihedral types" can be
    less than the largest type the file uses, which LAMMPS refuses. Put the largest."""
    with open(path) as f:
        lines = f.readlines()
    for attr in ("bonds", "angles", "dihedrals", "impropers"):
        most = max(int(t) for t in getattr(u, attr).types())
        word = attr[:-1] + " types"
        for k, line in enumerate(lines):
            if line.strip().endswith(word):
                lines[k] = "%12d  %s\n" % (most, word)
    with open(path, "w") as f:
        f.writelines(lines)


def lammps_box(dims):
    """LAMMPS box (lo, hi, xy, xz, yz) of a b c alpha beta gamma, origin 0."""
    a, b, c, al, be, ga = dims
    al, be, ga = np.radians([al, be, ga])
    lx = a
    xy = b * np.cos(ga)
    xz = c * np.cos(be)
    ly = np.sqrt(b * b - xy * xy)
    yz = (b * c * np.cos(al) - xy * xz) / ly
    lz = np.sqrt(c * c - xz * xz - yz * yz)
    h = np.array([[lx, xy, xz], [0, ly, yz], [0, 0, lz]])
    return h, (xy, xz, yz)


def write_dump(path, u, kind, cols, seed, box=BOX, nframes=None):
    h, tilt = lammps_box(box)
    hinv = np.linalg.inv(h)
    rng = np.random.default_rng(seed)
    lo = np.array([-5.0, -3.0, -4.0])
    xy, xz, yz = tilt
    xlo_b = lo[0] + min(0, xy, xz, xy + xz)
    xhi_b = lo[0] + h[0, 0] + max(0, xy, xz, xy + xz)
    ylo_b = lo[1] + min(0, yz)
    yhi_b = lo[1] + h[1, 1] + max(0, yz)
    with open(path, "w") as f:
        for ts in u.trajectory[:nframes]:
            pos = u.atoms.positions.astype(np.float64)
            s = (hinv @ (pos - lo).T).T          # fractional, unwrapped
            img = np.floor(s).astype(int)
            sw = s - img                          # fractional, wrapped into the box
            xw = (h @ sw.T).T + lo
            f.write("ITEM: TIMESTEP\n%d\n" % (100 * ts.frame))
            f.write("ITEM: NUMBER OF ATOMS\n%d\n" % u.atoms.n_atoms)
            if box[3:] == [90.0, 90.0, 90.0]:
                f.write("ITEM: BOX BOUNDS pp pp pp\n%.6f %.6f\n%.6f %.6f\n%.6f %.6f\n" % (
                    lo[0], lo[0] + h[0, 0], lo[1], lo[1] + h[1, 1], lo[2], lo[2] + h[2, 2]))
            else:
                f.write("ITEM: BOX BOUNDS xy xz yz pp pp pp\n")
                f.write("%.6f %.6f %.6f\n%.6f %.6f %.6f\n%.6f %.6f %.6f\n" % (
                    xlo_b, xhi_b, xy, ylo_b, yhi_b, xz, lo[2], lo[2] + h[2, 2], yz))
            f.write("ITEM: ATOMS %s\n" % " ".join(cols))
            vals = {"x": xw, "xs": sw, "xu": pos, "xsu": s}[kind]
            names = {"x": "x y z", "xs": "xs ys zs", "xu": "xu yu zu",
                     "xsu": "xsu ysu zsu"}[kind].split()
            for i in rng.permutation(u.atoms.n_atoms):
                field = {"id": "%d" % (i + 1), "type": u.atoms.types[i],
                         "mol": "%d" % u.atoms.resids[i],
                         "q": "%.4f" % u.atoms.charges[i],
                         "ix": "%d" % img[i, 0], "iy": "%d" % img[i, 1],
                         "iz": "%d" % img[i, 2]}
                for d, n in enumerate(names):
                    field[n] = "%.7f" % vals[i, d]
                f.write(" ".join(field[c] for c in cols) + "\n")


def main():
    u = mda.Universe(os.path.join(DATA, "helix.psf"), os.path.join(DATA, "helix.dcd"))
    make_data(u)
    variants = [("x", ["id", "type", "x", "y", "z", "ix", "iy", "iz"]),
                ("xs", ["type", "id", "ix", "iy", "iz", "xs", "ys", "zs", "q"]),
                ("xu", ["xu", "yu", "zu", "id", "mol", "type"]),
                ("xsu", ["id", "xsu", "ysu", "zsu", "type"])]
    for n, (kind, cols) in enumerate(variants):
        write_dump(os.path.join(DATA, "helix_%s.lammpstrj" % kind), u, kind, cols, 7 + n)
    write_dump(os.path.join(DATA, "helix_ortho.lammpstrj"), u, "x",
               ["id", "type", "x", "y", "z", "ix", "iy", "iz"], 3, [24.0, 26.0, 28.0, 90.0, 90.0, 90.0], 3)


if __name__ == "__main__":
    main()
