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


def seeds():
    """Seeds: the test files, and small cuts of them."""
    import shutil
    sets = {"poscar": ["POSCAR_spc", "CONTCAR_pept", "POSCAR4_pept", "POSCAR_negscale"],
            "xdatcar": ["XDATCAR_spc", "XDATCAR_npt"],
            "cor": ["helix.crd", "helix_ext.crd"], "dms": ["pept.dms"]}
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
    seeds()
