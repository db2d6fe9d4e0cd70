#!/usr/bin/python3
"""Make the test files of the third set of formats (tests/data/) and their fuzz seed corpora
(tests/fuzz/corpus/<fmt>/) from the structures in tests/data, with independent tools.

VASP (ase, python3-ase):
  POSCAR_spc      24 atoms of spc216.gro (sorted O then H), VASP 5, Direct, cubic cell
  CONTCAR_pept    the first 20 atoms of pept.pdb in a triclinic cell (10 11 12, 80 85 95),
                  VASP 5, Cartesian, selective dynamics (atoms 0-4 fixed)
  POSCAR4_pept    the same atoms as VASP 4 (species only in the comment line), Direct
  POSCAR_negscale POSCAR_spc with the lattice vectors halved and a negative scale factor
                  (the cell volume): the same structure (ase 3.22 cannot read it)
  XDATCAR_spc     POSCAR_spc's atoms in 3 frames (frame k moved by 0.1 k A), fixed cell
  XDATCAR_npt     the same frames, the header repeated before each with the cell scaled by
                  1 + 0.02 k (variable cell, the way VASP writes an NpT run)
CHARMM (MDAnalysis' CRD writer): helix.crd (standard) and helix_ext.crd (EXT) from
  helix.psf + the first frame of helix.dcd.
DMS (Python's sqlite3, the schema of Desmond's DMS files): pept.dms, helix.psf's first 60
  atoms with their masses, charges, bonds (order 2 for the C=O bonds), the first frame of
  helix.dcd, velocities i * (0.1, -0.2, 0.3) A/ps and an orthorhombic global_cell.

js (Python's struct, the layout of doc/js-format.md; no independent js writer exists):
  hand.js         5 atoms of one alanine (every optional field, 4 bonds with orders, one
                  angle), 2 frames with a cell (20 21 22, 90 90 120), native (little-endian)
                  byte order, no block padding
  hand_be.js      the same, big-endian, frames aligned to 512-byte blocks

Run from this folder: /usr/bin/python3 make_formats3.py
"""
import os
import sqlite3
import warnings

import numpy as np
import ase.io
from ase.constraints import FixAtoms
import MDAnalysis as mda

warnings.simplefilter("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
CORPUS = os.path.join(os.path.dirname(DATA), "fuzz", "corpus")


def path(name):
    return os.path.join(DATA, name)


def vasp():
    spc = ase.io.read(path("spc216.gro"))[:24]
    spc = spc[np.argsort([0 if s == "O" else 1 for s in spc.get_chemical_symbols()],
                         kind="stable")]
    ase.io.write(path("POSCAR_spc"), spc, format="vasp", direct=True, vasp5=True)
    pept = ase.io.read(path("pept.pdb"))[:20]
    pept.set_cell([10, 11, 12, 80, 85, 95], scale_atoms=False)
    pept.set_constraint(FixAtoms(indices=range(5)))
    ase.io.write(path("CONTCAR_pept"), pept, format="vasp", direct=False, vasp5=True)
    ase.io.write(path("POSCAR4_pept"), pept, format="vasp", direct=True, vasp5=False)
    lines = open(path("POSCAR_spc")).read().split("\n")
    vol = abs(np.linalg.det(spc.cell[:]))
    lines[1] = " -%.10f" % vol
    for k in range(2, 5):
        lines[k] = " ".join("%.10f" % (float(x) / 2) for x in lines[k].split())
    open(path("POSCAR_negscale"), "w").write("\n".join(lines))
    frames = []
    for k in range(3):
        f = spc.copy()
        f.positions += 0.1 * k
        f.wrap()
        frames.append(f)
    ase.io.write(path("XDATCAR_spc"), frames, format="vasp-xdatcar")
    head = open(path("XDATCAR_spc")).read().split("\n")[:7]
    with open(path("XDATCAR_npt"), "w") as out:
        for k, f in enumerate(frames):
            g = f.copy()
            g.set_cell(f.cell[:] * (1 + 0.02 * k), scale_atoms=True)
            out.write(head[0] + "\n 1.0\n")
            for v in g.cell[:]:
                out.write(" %14.8f %14.8f %14.8f\n" % tuple(v))
            out.write(head[5] + "\n" + head[6] + "\n")
            out.write("Direct configuration=%6d\n" % (k + 1))
            for p in g.get_scaled_positions():
                out.write(" %.8f %.8f %.8f\n" % tuple(p))


def charmm():
    os.chdir(DATA)   # relative names: the title line names helix.dcd without a folder
    u = mda.Universe("helix.psf", "helix.dcd")
    with mda.Writer(path("helix.crd"), u.atoms.n_atoms, format="CRD") as w:
        w.write(u.atoms)
    with mda.Writer(path("helix_ext.crd"), u.atoms.n_atoms, format="CRD", extended=True) as w:
        w.write(u.atoms)


ANUM = {1: 1, 12: 6, 14: 7, 16: 8, 32: 16}


def dms():
    u = mda.Universe(path("helix.psf"), path("helix.dcd"))
    atoms = u.atoms[:60]
    out = path("pept.dms")
    if os.path.exists(out):
        os.unlink(out)
    db = sqlite3.connect(out)
    db.executescript(
        "CREATE TABLE particle (id INTEGER PRIMARY KEY, anum INTEGER, name TEXT NOT NULL,"
        " x FLOAT, y FLOAT, z FLOAT, vx FLOAT, vy FLOAT, vz FLOAT, resname TEXT NOT NULL,"
        " resid INTEGER, chain TEXT NOT NULL, segid TEXT NOT NULL, mass FLOAT, charge FLOAT,"
        " formal_charge INTEGER, insertion TEXT NOT NULL, msys_ct INTEGER NOT NULL);"
        "CREATE TABLE bond (p0 INTEGER, p1 INTEGER, 'order' INTEGER);"
        "CREATE TABLE global_cell (id INTEGER PRIMARY KEY, x FLOAT, y FLOAT, z FLOAT);")
    for i, a in enumerate(atoms):
        db.execute("INSERT INTO particle VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)",
                   (i, ANUM.get(int(round(a.mass)), 0), a.name, *map(float, a.position),
                    0.1 * i, -0.2 * i, 0.3 * i, a.resname, int(a.resid), "A", a.segid,
                    float(a.mass), float(a.charge), 0, "", 0))
    for b in atoms.bonds:
        i, j = b.atoms.indices
        if i < 60 and j < 60:
            names = {b.atoms[0].name, b.atoms[1].name}
            db.execute("INSERT INTO bond VALUES (?,?,?)",
                       (int(i), int(j), 2 if names == {"C", "O"} else 1))
    for k, v in enumerate(([40.0, 0, 0], [0, 41.0, 0], [0, 0, 42.0])):
        db.execute("INSERT INTO global_cell VALUES (?,?,?,?)", (k + 1, *v))
    db.commit()
    db.close()


JS = {
    "name": ["N", "CA", "C", "O", "CB"], "type": ["NH1", "CT1", "C", "O", "CT3"],
    "resname": ["ALA"] * 5, "segid": ["PRO"] * 5, "chain": ["A"] * 5, "resid": [7] * 5,
    "occupancy": [1.0, 0.5, 1.0, 0.25, 1.0], "beta": [10.0, 11.0, 12.0, 13.0, 14.0],
    "mass": [14.007, 12.011, 12.011, 15.999, 12.011], "charge": [-0.47, 0.07, 0.51, -0.51, -0.27],
    "radius": [1.85, 2.275, 2.0, 1.7, 2.06], "anum": [7, 6, 6, 8, 6],
    "bonds": [(1, 2, 1.0), (2, 3, 1.0), (3, 4, 2.0), (2, 5, 1.0)],
    "cell": [20.0, 21.0, 22.0, 90.0, 90.0, 120.0],
}


def js_frame(k):
    """Coordinates of frame k: atom i at (i + k, 2 i, -i)."""
    return [c for i in range(5) for c in (i + k, 2.0 * i, -1.0 * i)]


def write_js(name, order, block):
    """A js file by the documented layout: header, option flags, (block size), string
    tables, index and value arrays, bonds, angles, then frames padded to `block` bytes."""
    import math
    import struct
    e = order
    opt = 0x1 | 0x2 | 0x4 | 0x8 | 0x100 | 0x200 | 0x400 | 0x800 | 0x1000 | 0x2000
    if block > 1:
        opt |= 0x10000000
    b = b"JS Binary Structure and Trajectory File Format"
    b += struct.pack(e + "6i", 0x31337, 0x12345678, 2, 9, 5, 2) + struct.pack(e + "i", opt)
    if block > 1:
        b += struct.pack(e + "i", block)
    tables = []
    for field, width in (("name", 16), ("type", 16), ("resname", 8), ("segid", 8),
                         ("chain", 2)):
        uniq = list(dict.fromkeys(JS[field]))
        tables.append((field, width, uniq))
    b += struct.pack(e + "5i", *[len(u) for _, _, u in tables])
    for _, width, uniq in tables:
        b += b"".join(s.encode().ljust(width, b"\0") for s in uniq)
    for field, _, uniq in tables:
        b += struct.pack(e + "5h", *[uniq.index(s) for s in JS[field]])
    b += struct.pack(e + "5i", *JS["resid"])
    for field in ("occupancy", "beta", "mass", "charge", "radius"):
        b += struct.pack(e + "5f", *JS[field])
    b += struct.pack(e + "5i", *JS["anum"])
    bonds = JS["bonds"]
    b += struct.pack(e + "i", len(bonds)) + struct.pack(e + "4i", *[x[0] for x in bonds])
    b += struct.pack(e + "4i", *[x[1] for x in bonds]) + struct.pack(e + "4f", *[x[2] for x in bonds])
    b += struct.pack(e + "i3i", 1, 1, 2, 3) + struct.pack(e + "i", 0) + struct.pack(e + "i", 0)
    pad = lambda data: data + b"\0" * ((block - len(data) % block) % block)
    c = JS["cell"]
    cell = struct.pack(e + "6d", c[0], c[1], c[2],
                       *[math.sin(math.radians(90.0 - a)) for a in c[3:]])
    out = pad(b)
    for k in range(2):
        out += pad(struct.pack(e + "15f", *js_frame(k))) + pad(cell)
    open(path(name), "wb").write(out)


def js():
    write_js("hand.js", "<", 1)
    write_js("hand_be.js", ">", 512)


def seeds():
    """Seeds: the test files, and small cuts of them."""
    import shutil
    sets = {"poscar": ["POSCAR_spc", "CONTCAR_pept", "POSCAR4_pept", "POSCAR_negscale"],
            "xdatcar": ["XDATCAR_spc", "XDATCAR_npt"],
            "cor": ["helix.crd", "helix_ext.crd"], "dms": ["pept.dms"],
            "js": ["hand.js", "hand_be.js"]}
    for fmt, names in sets.items():
        d = os.path.join(CORPUS, fmt)
        os.makedirs(d, exist_ok=True)
        for n in names:
            src = path(n)
            if fmt == "cor":   # the title, the count cut to 12 atoms, 12 atom lines
                lines = open(src).read().split("\n")
                k = next(i for i, l in enumerate(lines) if not l.startswith("*"))
                count = lines[k].split()
                lines[k] = lines[k].replace(count[0], "12".rjust(len(count[0])), 1)
                open(os.path.join(d, n), "w").write("\n".join(lines[:k + 13]) + "\n")
            else:
                shutil.copy(src, os.path.join(d, n))


if __name__ == "__main__":
    vasp()
    charmm()
    dms()
    js()
    seeds()
