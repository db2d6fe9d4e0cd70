#!/usr/bin/env python3
"""replicate_pdb.py: build a large system from a real structure by replicating it on a
lattice (real density, bonds and residues), for benchmarks. Each copy gets its own segment
name (S000, S001, ...) so residues stay distinct; serials are written in hybrid-36.

usage: replicate_pdb.py input.pdb natoms output.pdb
Prints the number of atoms written. Also importable: replicate(path, natoms) returns the
per-atom records and coordinates (used by bench_select.py to build MDAnalysis' copy)."""
import math
import sys

DIGITS_UPPER = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"


def hy36(value, width=5):
    """Hybrid-36 encoding as in the PDB format (decimal up to 99999, then base 36)."""
    if value < 10 ** width:
        return "%*d" % (width, value)
    value -= 10 ** width
    base = 26 * 36 ** (width - 1)
    if value < base:
        value += 10 * 36 ** (width - 1)
        s = ""
        for _ in range(width):
            s = DIGITS_UPPER[value % 36] + s
            value //= 36
        return s
    return "*" * width


def read_atoms(path):
    atoms = []
    for line in open(path):
        if line.startswith(("ATOM  ", "HETATM")):
            atoms.append(line.rstrip("\n").ljust(80))
    return atoms


def lattice(natoms, n1, extent, spacing_pad=8.0):
    copies = math.ceil(natoms / n1)
    side = math.ceil(copies ** (1.0 / 3.0))
    step = [e + spacing_pad for e in extent]
    offsets = []
    for k in range(copies):
        i, j, l = k % side, (k // side) % side, k // (side * side)
        offsets.append((i * step[0], j * step[1], l * step[2]))
    return offsets


def replicate(path, natoms):
    """Returns (records, xyz): records[i] = (record, name, resname, chain, resid, segid),
    xyz[i] = (x, y, z) rounded as the PDB writes them."""
    src = read_atoms(path)
    pos = [(float(l[30:38]), float(l[38:46]), float(l[46:54])) for l in src]
    lo = [min(p[k] for p in pos) for k in range(3)]
    hi = [max(p[k] for p in pos) for k in range(3)]
    offsets = lattice(natoms, len(src), [hi[k] - lo[k] for k in range(3)])
    records, xyz = [], []
    for c, off in enumerate(offsets):
        seg = "S%03d" % c if c < 1000 else hy36(c, 4)
        for l, p in zip(src, pos):
            if len(records) == natoms:
                return records, xyz
            records.append((l[0:6], l[12:16], l[17:20], l[21], int(l[22:26]), seg, l))
            xyz.append(tuple(round(p[k] + off[k], 3) for k in range(3)))
    return records, xyz


def write(records, xyz, out):
    with open(out, "w") as f:
        for i, (rec, name, resname, chain, resid, seg, line) in enumerate(records):
            x, y, z = xyz[i]
            f.write("%s%s %s%s%8.3f%8.3f%8.3f%s%-4s%s\n" % (
                rec, hy36(i + 1), line[12:30], "", x, y, z, line[54:72], seg, line[76:80]))
        f.write("END\n")


if __name__ == "__main__":
    records, xyz = replicate(sys.argv[1], int(sys.argv[2]))
    write(records, xyz, sys.argv[3])
    print(len(records))
