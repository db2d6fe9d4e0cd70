#!/usr/bin/python3
"""Write DCD variants no tool at hand writes, straight from the DCD layout (CHARMM's
dcdio: Fortran unformatted records, each framed by its byte length), with only the
Python standard library. Coordinates come from helix_amber.pdb (columns 31-54), so a
test knows every value without reading any DCD.

helix_be.dcd     big-endian, 32-bit markers, CHARMM version 24, unit cell as cosines:
                 A 40, B 41, C 42, alpha 70, beta 80, gamma 100 (frame k adds k to A).
                 3 frames: frame k = PDB + k * (1.0, 2.0, -0.5).
helix_fixed.dcd  little-endian, CHARMM, no cell, NAMNF = 130 fixed atoms (every atom
                 whose 1-based index is a multiple of 3). 4 frames: frame 0 holds all
                 atoms (the PDB); frame k > 0 holds only the 262 free atoms, at
                 PDB + k * (0.25, -0.5, 1.0); fixed atoms stay where frame 0 had them.
helix_4d64.dcd   little-endian, 64-bit record markers, CHARMM, 4D (a fourth coordinate
                 record per frame, filled with 99.0), unit cell in degrees
                 (50, 60, 70, 90, 90, 90). 2 frames: frame k = PDB + k * (-1, 0, 1).
helix_xplor.dcd  little-endian, X-PLOR (no CHARMM version, a double time step in the
                 control record, no cell). 2 frames: frame k = PDB + k * (0, 0, 3).

Run from this folder: /usr/bin/python3 make_dcd_variants.py  (writes into ..)
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)


def pdb_xyz(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith(("ATOM", "HETATM")):
                out.append((float(line[30:38]), float(line[38:46]), float(line[46:54])))
    return out


class Writer:
    def __init__(self, path, endian, marker):
        self.f = open(path, "wb")
        self.e = endian            # "<" or ">"
        self.m = marker            # "i" (32-bit) or "q" (64-bit)

    def record(self, payload):
        n = struct.pack(self.e + self.m, len(payload))
        self.f.write(n + payload + n)

    def header(self, nframes, natoms, charmm=True, cell=False, four_d=False, free=None):
        e = self.e
        icntrl = [0] * 20
        icntrl[0] = nframes
        icntrl[2] = 1
        icntrl[3] = nframes
        icntrl[8] = natoms - len(free) if free is not None else 0
        if charmm:
            ctl = struct.pack(e + "4s9if10i", b"CORD", *icntrl[:9], 0.02045,
                              1 if cell else 0, 1 if four_d else 0, *[0] * 7, 24)
        else:
            ctl = struct.pack(e + "4s9id9i", b"CORD", *icntrl[:9], 0.02045, *[0] * 9)
        assert len(ctl) == 84
        self.record(ctl)
        title = b"REMARKS made by tests/data/make/make_dcd_variants.py".ljust(80)
        self.record(struct.pack(e + "i", 1) + title)
        self.record(struct.pack(e + "i", natoms))
        if free is not None:
            self.record(struct.pack(e + "%di" % len(free), *[i + 1 for i in free]))

    def frame(self, xyz, cell=None, four_d=False):
        e = self.e
        if cell is not None:
            self.record(struct.pack(e + "6d", *cell))
        for d in range(3):
            self.record(struct.pack(e + "%df" % len(xyz), *[p[d] for p in xyz]))
        if four_d:
            self.record(struct.pack(e + "%df" % len(xyz), *[99.0] * len(xyz)))

    def close(self):
        self.f.close()


def moved(xyz, k, step):
    return [(x + k * step[0], y + k * step[1], z + k * step[2]) for x, y, z in xyz]


def main():
    xyz = pdb_xyz(os.path.join(DATA, "helix_amber.pdb"))
    n = len(xyz)
    cos = lambda deg: math.cos(math.radians(deg))

    w = Writer(os.path.join(DATA, "helix_be.dcd"), ">", "i")
    w.header(3, n, cell=True)
    for k in range(3):
        w.frame(moved(xyz, k, (1.0, 2.0, -0.5)), cell=(40.0 + k, cos(100), 41.0, cos(80), cos(70), 42.0))
    w.close()

    free = [i for i in range(n) if (i + 1) % 3 != 0]
    w = Writer(os.path.join(DATA, "helix_fixed.dcd"), "<", "i")
    w.header(4, n, free=free)
    w.frame(xyz)
    for k in range(1, 4):
        w.frame([p for i, p in enumerate(moved(xyz, k, (0.25, -0.5, 1.0))) if i in set(free)])
    w.close()

    w = Writer(os.path.join(DATA, "helix_4d64.dcd"), "<", "q")
    w.header(2, n, cell=True, four_d=True)
    for k in range(2):
        w.frame(moved(xyz, k, (-1.0, 0.0, 1.0)), cell=(50.0, 90.0, 60.0, 90.0, 90.0, 70.0), four_d=True)
    w.close()

    w = Writer(os.path.join(DATA, "helix_xplor.dcd"), "<", "i")
    w.header(2, n, charmm=False)
    for k in range(2):
        w.frame(moved(xyz, k, (0.0, 0.0, 3.0)))
    w.close()


if __name__ == "__main__":
    main()
