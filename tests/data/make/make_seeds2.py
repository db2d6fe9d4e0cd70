#!/usr/bin/python3
"""Make the fuzz seed corpora of the second set of readers (tests/fuzz/corpus/<fmt>/) and
the small test files of tests/data they share, from real structures and real tools.

xtc, trr: MDAnalysis writes 16 atoms of helix_amber.pdb in 2 frames (the XTC compressed)
     and 5 atoms (XTC's uncompressed form for 9 atoms or fewer).
cif: the first 40 atom_site rows of 3jqh.cif with its cell, struct_conf and assembly
     categories; a hand-written file with quoted values, a text field and two models.
pqr: the first 12 atoms of APBS' 1a63.pqr (no chain) and of small491.pqr (fixed columns).
mol2: the first molecule of PyMOL's small03.mol2, and the first two molecules.
namdbin: 16 atoms of pept.pdb as NAMD binary coordinates, native and byte-swapped, written
     here with struct (int32 count, float64 x y z).
dx, cube, ccp4: 3 x 4 x 5 grids of value i + 10 j + 100 k written here by hand (DX z
     fastest; cube in Bohr with two atoms); a CCP4 map of the same grid in mode 2 written
     here with struct, and one with axes ordered z x y.

Run from this folder: /usr/bin/python3 make_seeds2.py
"""
import gzip
import os
import struct

import MDAnalysis as mda

from seedpaths import DATA, out


def gromacs():
    u = mda.Universe(os.path.join(DATA, "helix_amber.pdb"))
    for ext in ("xtc", "trr"):
        for n, name in ((16, "helix16"), (5, "helix5")):
            with mda.Writer(out(ext, "%s.%s" % (name, ext)), n) as w:
                for k in range(2):
                    u.atoms.positions += 0.5 * k
                    w.write(u.atoms[:n])


def cif():
    lines = open(os.path.join(DATA, "3jqh.cif")).read().split("\n")
    keep, rows, in_atoms = [], 0, False
    for l in lines:
        if l.startswith("_atom_site."):
            in_atoms = True
        elif in_atoms and not l.startswith("_"):
            if l.startswith("#"):
                in_atoms = False
            elif rows >= 40:
                continue
            else:
                rows += 1
        keep.append(l)
    open(out("cif", "3jqh_cut.cif"), "w").write("\n".join(keep))
    open(out("cif", "quoted.cif"), "w").write("""data_test
# a comment
_cell.length_a 10.0
_cell.length_b 11.0
_cell.length_c 12.0(3)
_cell.angle_alpha 90
_cell.angle_beta 90
_cell.angle_gamma 90
_struct.title
;A title on
two lines
;
loop_
_atom_site.group_PDB
_atom_site.id
_atom_site.type_symbol
_atom_site.label_atom_id
_atom_site.label_alt_id
_atom_site.label_comp_id
_atom_site.label_asym_id
_atom_site.label_seq_id
_atom_site.Cartn_x
_atom_site.Cartn_y
_atom_site.Cartn_z
_atom_site.auth_seq_id
_atom_site.auth_asym_id
_atom_site.pdbx_PDB_model_num
ATOM 1 C "C1'" . 'A B' A 1 1.0 2.0 3.0 5 X 1
ATOM 2 O 'O2"' . 'A B' A 1 2.0 2.0 3.0 5 X 1
ATOM 1 C "C1'" . 'A B' A 1 1.5 2.5 3.5 5 X 2
ATOM 2 O 'O2"' . 'A B' A 1 2.5 2.5 3.5 5 X 2
#
""")


def pqr():
    for src, name in (("/usr/share/apbs/examples/pbam/1a63.pqr", "1a63_cut.pqr"),
                      ("/usr/share/apbs/examples/ion-protein/small491.pqr", "small491_cut.pqr")):
        atoms = [l for l in open(src) if l.startswith("ATOM")][:12]
        open(out("pqr", name), "w").write("".join(atoms) + "END\n")


def mol2():
    text = open("/usr/share/pymol/test/dat/small03.mol2").read()
    mols = text.split("@<TRIPOS>MOLECULE")
    open(out("mol2", "small03_1.mol2"), "w").write("@<TRIPOS>MOLECULE" + mols[1])
    open(out("mol2", "small03_2.mol2"), "w").write(
        "@<TRIPOS>MOLECULE" + mols[1] + "@<TRIPOS>MOLECULE" + mols[2])


def namdbin():
    u = mda.Universe(os.path.join(DATA, "pept.pdb"))
    xyz = u.atoms.positions[:16].astype(float).ravel()
    for order, name in (("<", "pept16_le.coor"), (">", "pept16_be.coor")):
        open(out("namdbin", name), "wb").write(
            struct.pack(order + "i", 16) + struct.pack(order + "48d", *xyz))


def value(i, j, k):
    return i + 10 * j + 100 * k


def grids():
    n = (3, 4, 5)
    vals = [value(i, j, k) for i in range(n[0]) for j in range(n[1]) for k in range(n[2])]
    body = "\n".join(" ".join("%g" % v for v in vals[p:p + 3]) for p in range(0, len(vals), 3))
    open(out("dx", "grid345.dx"), "w").write(
        "# a 3 x 4 x 5 grid\nobject 1 class gridpositions counts 3 4 5\norigin 1 2 3\n"
        "delta 0.5 0 0\ndelta 0 1 0\ndelta 0 0 2\n"
        "object 2 class gridconnections counts 3 4 5\n"
        "object 3 class array type double rank 0 items 60 data follows\n" + body +
        "\nattribute \"dep\" string \"positions\"\n")
    body = "\n".join(" ".join("%.5e" % v for v in vals[p:p + 6]) for p in range(0, len(vals), 6))
    open(out("cube", "grid345.cube"), "w").write(
        "a test cube\nvalues i + 10 j + 100 k\n    2    1.000000    2.000000    3.000000\n"
        "    3    0.500000    0.000000    0.000000\n    4    0.000000    1.000000    0.000000\n"
        "    5    0.000000    0.000000    2.000000\n"
        "    8    8.000000    1.000000    2.000000    3.000000\n"
        "    1    1.000000    2.000000    2.000000    3.000000\n" + body + "\n")
    for axes, name in (((1, 2, 3), "grid345.ccp4"), ((3, 1, 2), "grid345_zxy.ccp4")):
        open(out("ccp4", name), "wb").write(ccp4(n, axes))


def ccp4(n, axes):
    """A mode-2 map of value(i, j, k); columns, rows, sections along `axes` (1 = x)."""
    nc = [n[a - 1] for a in axes]
    h = bytearray(1024)
    struct.pack_into("<3i", h, 0, *nc)
    struct.pack_into("<i", h, 12, 2)
    struct.pack_into("<3i", h, 28, *n)
    struct.pack_into("<6f", h, 40, 1.5, 4.0, 10.0, 90, 90, 90)
    struct.pack_into("<3i", h, 64, *axes)
    h[208:212] = b"MAP "
    h[212:214] = b"\x44\x41"
    data = bytearray()
    for s in range(nc[2]):
        for r in range(nc[1]):
            for c in range(nc[0]):
                idx = [0, 0, 0]
                idx[axes[0] - 1], idx[axes[1] - 1], idx[axes[2] - 1] = c, r, s
                data += struct.pack("<f", value(*idx))
    return bytes(h) + bytes(data)


if __name__ == "__main__":
    gromacs()
    cif()
    pqr()
    mol2()
    namdbin()
    grids()
