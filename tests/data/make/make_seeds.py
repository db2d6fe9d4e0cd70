#!/usr/bin/python3
"""Make the fuzz seed corpora (tests/fuzz/corpus/<fmt>/): small files cut from the test
structures and written by real tools, one per variant a reader must handle.

pdb: the first residues of pept.pdb and tiny.pdb (cut by line), odd01/odd02/small02 as they are,
     and a two-model cut of helix_amber.pdb written by MDAnalysis.
psf: ParmEd writes the first two residues of helix_amber.pdb (CHEQ EXT XPLOR) and the same
     with integer (CHARMM) types in the standard columns; a NAMD space-separated cut of
     tests/data/helix.psf's first atoms with long segment names is written here by hand.
dcd: MDAnalysis writes a 16-atom, 3-frame DCD; make_dcd_variants.Writer writes the
     big-endian, fixed-atom, 64-bit/4D and X-PLOR variants of the same 16 atoms.
xyz: MDAnalysis writes 16 atoms in 2 frames; one frame with atomic numbers as names.
gro: MDAnalysis writes 16 atoms with velocities and a triclinic box; the first 6 atoms of
     spc216.gro twice (two frames).

Run from this folder: /usr/bin/python3 make_seeds.py
"""
import os

import numpy as np
import parmed
import parmed.formats.psf
import MDAnalysis as mda

import make_dcd_variants as v
from seedpaths import DATA, out


def head_lines(src, dst, n):
    with open(src) as f:
        lines = f.readlines()[:n]
    with open(dst, "w") as f:
        f.writelines(lines)


def pdb_seeds():
    head_lines(os.path.join(DATA, "pept.pdb"), out("pdb", "pept_head.pdb"), 40)
    head_lines(os.path.join(DATA, "tiny.pdb"), out("pdb", "tiny_head.pdb"), 24)
    for name in ("odd01.pdb", "odd02.pdb", "small02.pdb"):
        head_lines(os.path.join(DATA, name), out("pdb", name), 10000)
    u = mda.Universe(os.path.join(DATA, "helix_amber.pdb"))
    sel = u.atoms[:16]
    with mda.Writer(out("pdb", "helix_models.pdb"), multiframe=True) as w:
        for k in range(2):
            sel.positions = sel.positions + k
            w.write(sel)


def psf_seeds():
    s = parmed.load_file(os.path.join(DATA, "helix_amber.pdb"))[":1-2"]
    for i, a in enumerate(s.atoms):
        a.charge = 0.1 * (i % 5) - 0.2
    s.save(out("psf", "helix2_ext.psf"), overwrite=True)
    for i, a in enumerate(s.atoms):
        a.type = a.atomic_number + 10
    s.flags = []
    parmed.formats.psf.PSFFile.write(s, out("psf", "helix2_charmm.psf"))
    with open(out("psf", "namd.psf"), "w") as f:
        f.write("PSF NAMD\n\n       1 !NTITLE\n REMARKS cut by hand\n\n       4 !NATOM\n")
        f.write("1 PROTEINA 12A ALA N NH3 -0.300000 14.0070 0\n")
        f.write("2 PROTEINA 12A ALA HT1 HC 0.330000 1.0080 0\n")
        f.write("3 PROTEINA 12A ALA CA CT1 0.210000 12.0110 0\n")
        f.write("4 WATERLONGNAME 13 TIP3 OH2 OT -0.834000 15.9994 0\n\n")
        f.write("       3 !NBOND: bonds\n       1       2       1       3       2       3\n\n")


def dcd_seeds():
    u = mda.Universe(os.path.join(DATA, "helix_amber.pdb"))
    sel = u.atoms[:16]
    xyz0 = sel.positions.copy()
    with mda.Writer(out("dcd", "mda16.dcd"), 16) as w:
        for k in range(3):
            sel.positions = xyz0 + k
            u.dimensions = [20 + k, 21, 22, 80, 90, 100]
            w.write(sel)
    xyz = [tuple(map(float, p)) for p in xyz0]
    free = [i for i in range(16) if i % 3]
    w = v.Writer(out("dcd", "be16.dcd"), ">", "i")
    w.header(2, 16, cell=True)
    for k in range(2):
        w.frame(v.moved(xyz, k, (1, 1, 1)), cell=(20.0, 0.0, 21.0, 0.0, 0.0, 22.0))
    w.close()
    w = v.Writer(out("dcd", "fixed16.dcd"), "<", "i")
    w.header(3, 16, free=free)
    w.frame(xyz)
    for k in (1, 2):
        w.frame([p for i, p in enumerate(v.moved(xyz, k, (1, 0, 0))) if i in free])
    w.close()
    w = v.Writer(out("dcd", "4d64_16.dcd"), "<", "q")
    w.header(2, 16, cell=True, four_d=True)
    for k in range(2):
        w.frame(xyz, cell=(20.0, 90.0, 21.0, 90.0, 90.0, 22.0), four_d=True)
    w.close()
    w = v.Writer(out("dcd", "xplor16.dcd"), "<", "i")
    w.header(2, 16, charmm=False)
    for k in range(2):
        w.frame(xyz)
    w.close()


def xyz_gro_seeds():
    u = mda.Universe(os.path.join(DATA, "helix_amber.pdb"))
    sel = u.atoms[:16]
    with mda.Writer(out("xyz", "helix16.xyz"), 16) as w:
        for k in range(2):
            sel.positions = sel.positions + k
            w.write(sel)
    with open(out("xyz", "numbers.xyz"), "w") as f:
        f.write("3\nwater, atomic numbers as names\n8 0.0 0.0 0.0\n1 0.9572 0.0 0.0\n"
                "1 -0.24 0.9266 0.0\n")
    u.dimensions = [30, 32, 34, 80, 95, 100]
    sel.write(out("gro", "helix16.gro"))
    uv = mda.Universe(os.path.join(DATA, "spc216.gro"))
    w6 = uv.atoms[:6]
    uv.add_TopologyAttr("tempfactors")
    w6.write(out("gro", "spc6.gro"))
    with open(out("gro", "spc6.gro")) as f:
        one = f.read()
    with open(out("gro", "spc6x2.gro"), "w") as f:
        f.write(one + one.replace("Written by MDAnalysis", "frame two t= 2.0"))
    os.remove(out("gro", "spc6.gro"))
    # velocities: a hand-extended copy of the first helix16 lines
    with open(out("gro", "helix16.gro")) as f:
        lines = f.read().splitlines()
    body = [l + "  0.1000 -0.2000  0.3000" for l in lines[2:-1]]
    with open(out("gro", "helix16_vel.gro"), "w") as f:
        f.write("\n".join(lines[:2] + body + lines[-1:]) + "\n")


if __name__ == "__main__":
    pdb_seeds()
    psf_seeds()
    dcd_seeds()
    xyz_gro_seeds()
