# vmd_style.py: a VMD-style Python analysis, written from VMD's Python documentation (the
# vmd module's molecule, atomsel, vmdnumpy and evaltcl), run unmodified by
# `molscope -python -e vmd_style.py` and, with only the import line changed, by a plain
# python3 (test_embedded.py compares the two outputs).
from vmd import molecule, atomsel, vmdnumpy, evaltcl
import os

data = os.environ["MS_TEST_DATA"]
mol = molecule.load("psf", os.path.join(data, "helix.psf"), "dcd", os.path.join(data, "helix.dcd"))
print("molecule %d: %d atoms, %d frames" % (mol, molecule.numatoms(mol), molecule.numframes(mol)))

ref = atomsel("name CA", molid=mol, frame=0)
ca = atomsel("name CA", molid=mol)
everything = atomsel("all", molid=mol)
for frame in range(molecule.numframes(mol)):
    ca.frame = frame
    everything.frame = frame
    before = ca.rmsd(ref)
    everything.move(ca.fit(ref))
    print("frame %d before %.3f rmsd %.3f rgyr %.3f" % (frame, before, ca.rmsd(ref), ca.rgyr()))

xyz = vmdnumpy.timestep(mol, 0)
print("center %.3f %.3f %.3f" % tuple(xyz.mean(axis=0)))
print("residues", len(set(atomsel("protein", molid=mol).get("resid"))))
print("tcl says", evaltcl("molinfo %d get numatoms" % mol))
molecule.delete(mol)
print("left", molecule.listall())
