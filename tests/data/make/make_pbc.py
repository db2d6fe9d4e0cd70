#!/usr/bin/python3
"""Make the periodic water trajectories of the pbc tests from spc216.gro with real tools.

The 216 SPC waters of spc216.gro (GROMACS' water box) in a triclinic cell whose edges
change a little per frame: frame k has cell (18.62 + 0.1 k, 19.0, 19.5 - 0.05 k, 80, 85, 95).

water_tric_cont.dcd: 6 frames of continuous motion (no atom jumps). Frame 0 is the GRO's
  coordinates wrapped atom by atom into cell 0 by MDAnalysis' apply_PBC (so some molecules
  are split across the boundary, as in a wrapped MD trajectory); each later frame moves every
  molecule by a random step (normal, sigma 1.6 A per axis, seed 19) and every atom by a
  little noise (sigma 0.05 A), so molecules cross the cell's faces.
water_tric.dcd: the same frames wrapped atom by atom into each frame's cell by apply_PBC:
  what an MD engine writes. `pbc unwrap` of it must give water_tric_cont.dcd back.

Both written by MDAnalysis' DCDWriter (CHARMM DCD with the unit cell).
Run from this folder: /usr/bin/python3 make_pbc.py  (writes into ..)
"""
import os
import warnings

import numpy as np
import MDAnalysis as mda
from MDAnalysis.lib.distances import apply_PBC

warnings.simplefilter("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
NFRAMES = 6


def cell(k):
    return np.array([18.62 + 0.1 * k, 19.0, 19.5 - 0.05 * k, 80.0, 85.0, 95.0], dtype=np.float32)


def main():
    u = mda.Universe(os.path.join(DATA, "spc216.gro"))
    rng = np.random.default_rng(19)
    resindex = u.atoms.resindices
    pos = apply_PBC(u.atoms.positions.astype(np.float32), cell(0))
    frames = [pos.copy()]
    for k in range(1, NFRAMES):
        step = rng.normal(0.0, 1.6, size=(u.residues.n_residues, 3))
        noise = rng.normal(0.0, 0.05, size=pos.shape)
        pos = (pos + step[resindex] + noise).astype(np.float32)
        frames.append(pos.copy())
    write(u, "water_tric_cont.dcd", frames)
    write(u, "water_tric.dcd", [apply_PBC(p, cell(k)) for k, p in enumerate(frames)])


def write(u, name, frames):
    with mda.Writer(os.path.join(DATA, name), u.atoms.n_atoms) as w:
        for k, p in enumerate(frames):
            u.atoms.positions = p
            u.dimensions = cell(k)
            w.write(u.atoms)


if __name__ == "__main__":
    main()
