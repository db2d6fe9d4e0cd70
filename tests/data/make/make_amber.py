#!/usr/bin/python3
"""Make the AMBER test files (tests/data/helix*.prmtop ...) and the seed corpora of the
AMBER readers (tests/fuzz/corpus/{parm7,rst7,crd,crdbox,netcdf}/) with real tools.

ParmEd (Debian python3-parmed) cannot parametrize the helix without a force field, so the
topology is built from helix.psf (392 atoms, 399 bonds, charges and masses) with made-up
parameters: angles and proper dihedrals are every path of 3 and 4 bonded atoms, an improper
sits on every atom with exactly three bonded neighbours, and every fourth dihedral gets a
second Fourier term (AMBER writes it again with its third index negative). Each atom's type
is the first two letters of its name, its atomic number that of the name's first letter. ParmEd's AmberParm writes the new-style topology
(%FLAG/%FORMAT) with a box (IFBOX 1).

helix.prmtop       ParmEd, 392 atoms, box 30 32 34, ATOMIC_NUMBER present
helix_old.parm     the same topology in the old (pre-AMBER 7) layout: a title line, then
                   the sections in their fixed order, 20A4 / 12I6 / 5E16.8 (written here
                   from ParmEd's parsed sections; no tool writes the old layout any more)
helix.rst7         ParmEd Rst7: frame 0 of helix.dcd, velocities, box, time 12.5
helix.inpcrd       ParmEd Rst7: frame 1, no velocities, no box
helix.mdcrd        ParmEd AmberMdcrd: frames 0-4 of helix.dcd, no box
helix.crdbox       ParmEd AmberMdcrd: frames 0-4 with their box lengths
helix.nc           MDAnalysis NCDFWriter: the 10 frames of helix.dcd with their cells
helix_vel.nc       netCDF4 (python3-netcdf4), AMBER convention: 3 frames with velocities
                   (scale_factor 20.455), times 1.5, 3.0, 4.5 ps, no cell
helix.ncrst        ParmEd NetCDFRestart: frame 2, velocities, box

Seeds: the same files cut to the first residue (ACE, 6 atoms) or to 5 atoms (the count the
crd fuzz targets add frames to).

Run from this folder: /usr/bin/python3 make_amber.py  (writes into .. and ../../fuzz/corpus)
"""
import os
import warnings

import numpy as np
import parmed
from parmed import amber
import MDAnalysis as mda
import netCDF4

warnings.simplefilter("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
CORPUS = os.path.join(DATA, "..", "fuzz", "corpus")
ELEMENT = {"H": 1, "C": 6, "N": 7, "O": 8, "S": 16}


def paths_from_bonds(s):
    nbr = {a.idx: sorted(b.idx for b in a.bond_partners) for a in s.atoms}
    angles, diheds = [], []
    for j in nbr:
        for i in nbr[j]:
            for k in nbr[j]:
                if i < k:
                    angles.append((i, j, k))
    for j in nbr:
        for k in nbr[j]:
            if j >= k:
                continue
            for i in nbr[j]:
                for l in nbr[k]:
                    if i != k and l != j and i != l:
                        diheds.append((i, j, k, l))
    return nbr, angles, diheds


def build(psf):
    """A parametrized Structure from the PSF: fake but complete AMBER parameters."""
    s = parmed.load_file(psf)
    s.box = [30.0, 32.0, 34.0, 90.0, 90.0, 90.0]
    types = {}
    for a in s.atoms:
        a.atomic_number = ELEMENT[a.name.lstrip("0123456789")[0]]  # the PSF has no elements
        name = a.name[:2]
        if name not in types:
            t = parmed.AtomType(name, len(types) + 1, a.mass, a.atomic_number)
            t.set_lj_params(0.1 + 0.01 * len(types), 1.5 + 0.05 * len(types))
            types[name] = t
        a.type, a.atom_type = name, types[name]
    bt = parmed.BondType(300.0, 1.4, list=s.bond_types)
    s.bond_types.append(bt)
    for b in s.bonds:
        b.type = bt
    at = parmed.AngleType(50.0, 109.5, list=s.angle_types)
    s.angle_types.append(at)
    nbr, angles, diheds = paths_from_bonds(s)
    A = s.atoms
    for i, j, k in angles:
        s.angles.append(parmed.Angle(A[i], A[j], A[k], type=at))
    d1 = parmed.DihedralType(1.0, 3, 0.0, list=s.dihedral_types)
    d2 = parmed.DihedralType(0.5, 2, 180.0, list=s.dihedral_types)
    di = parmed.DihedralType(10.5, 2, 180.0, list=s.dihedral_types)
    s.dihedral_types.extend([d1, d2, di])
    for n, (i, j, k, l) in enumerate(diheds):
        s.dihedrals.append(parmed.Dihedral(A[i], A[j], A[k], A[l], type=d1))
        if n % 4 == 0:
            s.dihedrals.append(parmed.Dihedral(A[i], A[j], A[k], A[l], type=d2,
                                               ignore_end=True))
    for c, ns in nbr.items():
        if len(ns) == 3:
            s.dihedrals.append(parmed.Dihedral(A[ns[0]], A[ns[1]], A[c], A[ns[2]],
                                               improper=True, ignore_end=True, type=di))
    return amber.AmberParm.from_structure(s)


OLD_ORDER = [  # (flag, kind) in the old layout's order
    ("ATOM_NAME", "a"), ("CHARGE", "E"), ("MASS", "E"), ("ATOM_TYPE_INDEX", "I"),
    ("NUMBER_EXCLUDED_ATOMS", "I"), ("NONBONDED_PARM_INDEX", "I"), ("RESIDUE_LABEL", "a"),
    ("RESIDUE_POINTER", "I"), ("BOND_FORCE_CONSTANT", "E"), ("BOND_EQUIL_VALUE", "E"),
    ("ANGLE_FORCE_CONSTANT", "E"), ("ANGLE_EQUIL_VALUE", "E"), ("DIHEDRAL_FORCE_CONSTANT", "E"),
    ("DIHEDRAL_PERIODICITY", "E"), ("DIHEDRAL_PHASE", "E"), ("SOLTY", "E"),
    ("LENNARD_JONES_ACOEF", "E"), ("LENNARD_JONES_BCOEF", "E"), ("BONDS_INC_HYDROGEN", "I"),
    ("BONDS_WITHOUT_HYDROGEN", "I"), ("ANGLES_INC_HYDROGEN", "I"),
    ("ANGLES_WITHOUT_HYDROGEN", "I"), ("DIHEDRALS_INC_HYDROGEN", "I"),
    ("DIHEDRALS_WITHOUT_HYDROGEN", "I"), ("EXCLUDED_ATOMS_LIST", "I"), ("HBOND_ACOEF", "E"),
    ("HBOND_BCOEF", "E"), ("HBCUT", "E"), ("AMBER_ATOM_TYPE", "a"),
    ("TREE_CHAIN_CLASSIFICATION", "a"), ("JOIN_ARRAY", "I"), ("IROTAT", "I"),
    ("SOLVENT_POINTERS", "I"), ("ATOMS_PER_MOLECULE", "I"), ("BOX_DIMENSIONS", "E")]


def old_lines(values, kind):
    per, fmt = {"a": (20, "%-4s"), "I": (12, "%6d"), "E": (5, "%16.8E")}[kind]
    out = []
    for i in range(0, len(values), per):
        out.append("".join(fmt % v for v in values[i:i + per]))
    return out or [""]


def write_old(parm, path):
    """The old layout: title, 30 pointers (12I6), then the sections in order."""
    lines = ["%-80s" % "helix, old-style AMBER topology written by make_amber.py"]
    lines += old_lines(parm.parm_data["POINTERS"][:30], "I")
    for flag, kind in OLD_ORDER:
        if flag in ("SOLVENT_POINTERS", "ATOMS_PER_MOLECULE", "BOX_DIMENSIONS") and \
                parm.parm_data["POINTERS"][27] == 0:
            continue
        values = parm.parm_data[flag]
        if flag == "CHARGE":  # ParmEd keeps charges in e once parsed: back to AMBER units
            values = [q * 18.2223 for q in values]
        lines += old_lines(values, kind)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def frames(psf, dcd):
    u = mda.Universe(psf, dcd)
    return [(ts.positions.astype(np.float64).copy(), ts.dimensions.copy()) for ts in u.trajectory]


def write_rst7(path, xyz, box=None, vel=None, time=0.0, netcdf=False):
    r = amber.Rst7(natom=len(xyz), title="helix from make_amber.py")
    r.time = time
    r.coordinates = xyz
    if vel is not None:
        r.vels = vel
    if box is not None:
        r.box = list(box)
    r.write(path, netcdf=netcdf)


def write_mdcrd(path, fr, box):
    f = amber.AmberMdcrd(path, len(fr[0][0]), hasbox=box, mode="w", title="helix mdcrd")
    for xyz, dims in fr:
        f.add_coordinates(xyz)
        if box:
            f.add_box(dims[:3])
    f.close()


def write_ncdf(path, psf, dcd, n=None):
    u = mda.Universe(psf, dcd)
    ag = u.atoms if n is None else u.atoms[:n]
    with mda.Writer(path, ag.n_atoms) as w:
        for ts in u.trajectory:
            w.write(ag)


def write_vel_nc(path, fr, n=None):
    """The AMBER convention by hand with netCDF4: velocities and times, no cell."""
    nat = len(fr[0][0]) if n is None else n
    ds = netCDF4.Dataset(path, "w", format="NETCDF3_64BIT_OFFSET")
    ds.Conventions, ds.ConventionVersion, ds.program = "AMBER", "1.0", "make_amber.py"
    ds.createDimension("frame", None)
    ds.createDimension("spatial", 3)
    ds.createDimension("atom", nat)
    ds.createVariable("spatial", "c", ("spatial",))[:] = np.array(list("xyz"), "S1")
    t = ds.createVariable("time", "f4", ("frame",))
    t.units = "picosecond"
    c = ds.createVariable("coordinates", "f4", ("frame", "atom", "spatial"))
    c.units = "angstrom"
    v = ds.createVariable("velocities", "f4", ("frame", "atom", "spatial"))
    v.units, v.scale_factor = "angstrom/picosecond", 20.455
    v.set_auto_scale(False)
    for k in range(3):
        xyz = fr[k][0][:nat]
        c[k] = xyz
        v[k] = (0.01 * (k + 1)) * xyz[:, [1, 2, 0]]
        t[k] = 1.5 * (k + 1)
    ds.close()


def seeds(parm, fr, psf, dcd):
    for fmt in ("parm7", "rst7", "crd", "crdbox", "netcdf"):
        os.makedirs(os.path.join(CORPUS, fmt), exist_ok=True)
    ace = parm[":1"]  # the first residue: 6 atoms with bonds, angles and dihedrals
    ace.write_parm(os.path.join(CORPUS, "parm7", "ace.prmtop"))
    write_old(ace, os.path.join(CORPUS, "parm7", "ace_old.parm"))
    n = 5
    small = [(xyz[:n], dims) for xyz, dims in fr[:3]]
    write_rst7(os.path.join(CORPUS, "rst7", "five.rst7"), small[0][0], small[0][1][:6],
               0.1 * small[1][0], 3.0)
    write_rst7(os.path.join(CORPUS, "rst7", "five.inpcrd"), small[1][0])
    write_mdcrd(os.path.join(CORPUS, "crd", "five.mdcrd"), small, False)
    write_mdcrd(os.path.join(CORPUS, "crdbox", "five.crdbox"), small, True)
    write_ncdf(os.path.join(CORPUS, "netcdf", "five.nc"), psf, dcd, n)
    write_vel_nc(os.path.join(CORPUS, "netcdf", "five_vel.nc"), fr, n)
    write_rst7(os.path.join(CORPUS, "netcdf", "five.ncrst"), small[2][0], small[2][1][:6],
               0.2 * small[0][0], 7.0, netcdf=True)


def main():
    psf, dcd = os.path.join(DATA, "helix.psf"), os.path.join(DATA, "helix.dcd")
    parm = build(psf)
    parm.write_parm(os.path.join(DATA, "helix.prmtop"))
    parm = amber.AmberParm(os.path.join(DATA, "helix.prmtop"))
    write_old(parm, os.path.join(DATA, "helix_old.parm"))
    fr = frames(psf, dcd)
    write_rst7(os.path.join(DATA, "helix.rst7"), fr[0][0], fr[0][1][:6], 0.1 * fr[1][0], 12.5)
    write_rst7(os.path.join(DATA, "helix.inpcrd"), fr[1][0])
    write_mdcrd(os.path.join(DATA, "helix.mdcrd"), fr[:5], False)
    write_mdcrd(os.path.join(DATA, "helix.crdbox"), fr[:5], True)
    write_ncdf(os.path.join(DATA, "helix.nc"), psf, dcd)
    write_vel_nc(os.path.join(DATA, "helix_vel.nc"), fr)
    write_rst7(os.path.join(DATA, "helix.ncrst"), fr[2][0], fr[2][1][:6], 0.2 * fr[0][0], 25.0,
               netcdf=True)
    seeds(parm, fr, psf, dcd)


if __name__ == "__main__":
    main()
