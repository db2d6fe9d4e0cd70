#!/usr/bin/python3
"""make_polyhedra.py: writes tests/data/polyhedra.pdb, three coordination polyhedra with their
bonds as CONECT records, from ideal geometry (not from any program that draws polyhedra):
a TiO6 octahedron (Ti-O 1.95 A) at the origin, an SiO4 tetrahedron (Si-O 1.62 A) at
x = 6, and a CsCl8 cube (Cs-Cl 3.08 A) at y = 6. Their hulls have 8, 4 and 12 triangles.
usage: /usr/bin/python3 tests/data/make/make_polyhedra.py > tests/data/polyhedra.pdb"""
import itertools
import math

atoms = []      # (name, element, resname, x, y, z)
bonds = []


def centre(name, el, res, c, ligands, lname, lel):
    ci = len(atoms)
    atoms.append((name, el, res, *c))
    for v in ligands:
        bonds.append((ci, len(atoms)))
        atoms.append((lname, lel, res, c[0] + v[0], c[1] + v[1], c[2] + v[2]))


octa = [(s * 1.95 * (k == 0), s * 1.95 * (k == 1), s * 1.95 * (k == 2))
        for k in range(3) for s in (1, -1)]
a = 1.62 / math.sqrt(3)
tetra = [(a * x, a * y, a * z) for x, y, z in itertools.product((1, -1), repeat=3)
         if x * y * z > 0]
b = 3.08 / math.sqrt(3)
cube = [(b * x, b * y, b * z) for x, y, z in itertools.product((1, -1), repeat=3)]
centre("TI", "TI", "TIO", (0, 0, 0), octa, "O", "O")
centre("SI", "SI", "SIO", (6, 0, 0), tetra, "O", "O")
centre("CS", "CS", "CSC", (0, 6, 0), cube, "CL", "CL")

print("REMARK   made by tests/data/make/make_polyhedra.py")
for i, (name, el, res, x, y, z) in enumerate(atoms):
    print("HETATM%5d %-4s %3s A%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2s" %
          (i + 1, name, res, 1, x, y, z, el))
for c in sorted({i for i, _ in bonds}):
    partners = [j + 1 for i, j in bonds if i == c]
    for k in range(0, len(partners), 4):
        print("CONECT%5d" % (c + 1) + "".join("%5d" % p for p in partners[k:k + 4]))
print("END")
