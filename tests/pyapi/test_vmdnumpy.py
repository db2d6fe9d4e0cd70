"""test_vmdnumpy.py: vmdnumpy's arrays are molscope's own coordinates: float32, natoms x 3,
no copy (writing one moves the atoms Tcl sees, Tcl's moves show in the array), and safe
when the frame or the molecule goes (the array keeps its data, nothing crashes; asking for
a deleted molecule raises ValueError)."""
import numpy as np
import pytest

from molscope import vmdnumpy, molecule, atomsel
from conftest import data, tcl, tcl_list


def test_shape_type_values(helix):
    a = vmdnumpy.timestep(helix, 2)
    assert a.shape == (392, 3) and a.dtype == np.float32 and a.flags.writeable
    want = [float(x) for x in tcl_list("[atomselect %d all frame 2] get x" % helix)]
    assert a[:, 0].tolist() == pytest.approx(want)
    molecule.set_frame(helix, 2)
    assert np.shares_memory(vmdnumpy.positions(), a)


def test_writes_move_atoms_both_ways(helix):
    a = vmdnumpy.timestep(helix, 0)
    x0 = a[0].copy()
    a += np.float32(1.5)
    got = [float(x) for x in tcl_list("[atomselect %d {index 0} frame 0] get {x y z}" % helix)[0].split()]
    assert got == pytest.approx((x0 + 1.5).tolist(), abs=1e-5)
    tcl("[atomselect %d {index 0} frame 0] moveby {10 0 0}" % helix)
    assert a[0, 0] == pytest.approx(x0[0] + 11.5, abs=1e-4)
    assert np.shares_memory(vmdnumpy.timestep(helix, 0), a)
    assert not np.shares_memory(vmdnumpy.timestep(helix, 1), a)


def test_deleted_frame_and_molecule_do_not_crash(helix):
    a = vmdnumpy.timestep(helix, 0)
    keep = a.copy()
    molecule.delframe(helix, 0, 0)
    assert np.array_equal(a, keep)       # detached: the data stays readable
    a += 1                                # and writable, moving no atom any more
    assert molecule.numframes(helix) == 9
    c = vmdnumpy.timestep(helix, 8)
    molecule.delete(helix)
    assert float(c.sum()) == float(c.sum())
    with pytest.raises(ValueError) as e:
        vmdnumpy.timestep(helix, 0)
    assert "no molecule" in str(e.value)
    m = molecule.load("pdb", data("tiny.pdb"))
    with pytest.raises(ValueError):
        vmdnumpy.timestep(m, 5)


def test_atomselect_flags(helix):
    f = vmdnumpy.atomselect(helix, 0, "name CA")
    assert f.shape == (392,) and int(f.sum()) == len(atomsel("name CA", helix))
    assert np.flatnonzero(f).tolist() == list(atomsel("name CA", helix))
