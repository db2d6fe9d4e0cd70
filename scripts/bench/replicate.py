#!/usr/bin/env python3
"""replicate.py: build a large system from a real structure by lattice replication.

    replicate.py input.pdb natoms output.pdb

Copies the input's ATOM/HETATM records on a cubic-ish lattice (spacing = the structure's
extent plus 4 A) until at least `natoms` atoms, each copy with its own 4-character segment
id so residues stay distinct. Serial numbers above 99999 and residue numbers above 9999 are
written in hybrid-36, as the PDB format prescribes. Plain text processing: no dependencies.
"""
import math
import sys

DIG_U = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"


def hy36(value, width):
    """Encode value in hybrid-36 of the given width."""
    if value < 10 ** width:
        return "%*d" % (width, value)
    value -= 10 ** width
    value += 10 * 36 ** (width - 1)
    digits = []
    for _ in range(width):
        digits.append(DIG_U[value % 36])
        value //= 36
    return "".join(reversed(digits))


def main():
    src, want, dst = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    atoms = [l.rstrip("\n") for l in open(src) if l.startswith(("ATOM  ", "HETATM"))]
    xyz = [(float(l[30:38]), float(l[38:46]), float(l[46:54])) for l in atoms]
    lo = [min(p[k] for p in xyz) for k in range(3)]
    hi = [max(p[k] for p in xyz) for k in range(3)]
    step = [hi[k] - lo[k] + 4.0 for k in range(3)]
    copies = math.ceil(want / len(atoms))
    side = math.ceil(copies ** (1.0 / 3.0))
    serial = 0
    with open(dst, "w") as out:
        out.write("REMARK   1 %d COPIES OF %s ON A LATTICE\n" % (copies, src.split("/")[-1]))
        for c in range(copies):
            ix, iy, iz = c % side, (c // side) % side, c // (side * side)
            d = (ix * step[0], iy * step[1], iz * step[2])
            seg = hy36(c, 4).strip().rjust(4, "0")[-4:]
            for l, p in zip(atoms, xyz):
                serial += 1
                rec = l.ljust(80)
                out.write("%s%s%s%8.3f%8.3f%8.3f%s%-4s%s\n" % (
                    rec[:6], hy36(serial, 5), rec[11:30], p[0] + d[0], p[1] + d[1],
                    p[2] + d[2], rec[54:72], seg, rec[76:80].rstrip()))
        out.write("END\n")
    print("%s: %d atoms (%d copies of %d)" % (dst, serial, copies, len(atoms)))


if __name__ == "__main__":
    main()
