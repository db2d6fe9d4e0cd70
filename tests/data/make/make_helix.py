#!/usr/bin/python3
"""Make helix.psf, helix.dcd, helix.xyz and helix.gro from helix_amber.pdb with real tools.

helix.psf: ParmEd (Debian python3-parmed) reads the PDB, assigns bonds from its residue
  templates and writes a CHARMM PSF (flags CHEQ EXT XPLOR). The PDB has no charges, so each
  atom gets a made-up charge from its element (CHARGE below) plus 0.001 * (index % 7), and
  the two chains become segments HLXA and HLXB.
helix.dcd: MDAnalysis (Debian python3-mdanalysis) writes 10 frames (CHARMM DCD, unit cell
  in degrees). Frame k is the PDB rotated by 12*k degrees about the z axis through the
  origin, then moved by (0.5*k, -0.25*k, 0.1*k); its cell is
  (30+k, 32, 34+0.5*k, 80, 95, 100+k).
helix.xyz: MDAnalysis writes frames 0, 1 and 2 of the same trajectory as XYZ.
helix.gro: MDAnalysis writes frame 3 as GRO (nm, triclinic box).

Run from this folder: /usr/bin/python3 make_helix.py  (writes into ..)
"""
import math
import os
import warnings

import numpy as np
import parmed
import MDAnalysis as mda

warnings.simplefilter("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
CHARGE = {"H": 0.09, "C": -0.18, "N": -0.47, "O": -0.51, "S": -0.09}


def frame_xyz(xyz, k):
    a = math.radians(12.0 * k)
    c, s = math.cos(a), math.sin(a)
    out = np.empty_like(xyz)
    out[:, 0] = c * xyz[:, 0] - s * xyz[:, 1] + 0.5 * k
    out[:, 1] = s * xyz[:, 0] + c * xyz[:, 1] - 0.25 * k
    out[:, 2] = xyz[:, 2] + 0.1 * k
    return out


def cell(k):
    return np.array([30.0 + k, 32.0, 34.0 + 0.5 * k, 80.0, 95.0, 100.0 + k], dtype=np.float32)


def main():
    pdb = os.path.join(DATA, "helix_amber.pdb")
    s = parmed.load_file(pdb)
    for res in s.residues:
        res.segid = "HLXB" if res.chain == "B" else "HLXA"
    for i, atom in enumerate(s.atoms):
        atom.charge = CHARGE[atom.element_name] + 0.001 * (i % 7)
    s.save(os.path.join(DATA, "helix.psf"), overwrite=True)

    u = mda.Universe(os.path.join(DATA, "helix.psf"), pdb)
    xyz0 = u.atoms.positions.astype(np.float64)
    with mda.Writer(os.path.join(DATA, "helix.dcd"), u.atoms.n_atoms) as w:
        for k in range(10):
            u.atoms.positions = frame_xyz(xyz0, k)
            u.dimensions = cell(k)
            w.write(u.atoms)
    with mda.Writer(os.path.join(DATA, "helix.xyz"), u.atoms.n_atoms) as w:
        for k in range(3):
            u.atoms.positions = frame_xyz(xyz0, k)
            w.write(u.atoms)
    u.atoms.positions = frame_xyz(xyz0, 3)
    u.dimensions = cell(3)
    u.atoms.write(os.path.join(DATA, "helix.gro"))


if __name__ == "__main__":
    main()
