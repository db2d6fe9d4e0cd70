"""test_molecule.py: molscope.molecule against the mol/molinfo/animate commands it wraps:
the same ids, counts, names, files and frames; bad input raises TclError with the Tcl
command's own message and leaves no molecule behind."""
import pytest

from molscope import molecule, atomsel, TclError
from molscope._tcl import split
from conftest import data, tcl, tcl_list, tcl_error


def test_load_agrees_with_molinfo(helix):
    assert helix == int(tcl("molinfo top"))
    assert molecule.numatoms(helix) == int(tcl("molinfo %d get numatoms" % helix)) == 392
    assert molecule.numframes(helix) == int(tcl("molinfo %d get numframes" % helix)) == 10
    files = split(tcl_list("molinfo %d get filename" % helix)[0])
    assert molecule.get_filenames(helix) == files == [data("helix.psf"), data("helix.dcd")]
    assert molecule.get_filetypes(helix) == split(
        tcl_list("molinfo %d get filetype" % helix)[0]) == ["psf", "dcd"]
    assert molecule.name(helix) == tcl("molinfo %d get name" % helix)


def test_load_structure_only():
    m = molecule.load("pdb", data("tiny.pdb"))
    assert molecule.numatoms(m) == int(tcl("molinfo %d get numatoms" % m))
    assert molecule.numframes(m) == 1


def test_load_missing_file_is_tcl_error_and_leaves_nothing():
    before = molecule.listall()
    with pytest.raises(TclError) as e:
        molecule.load("pdb", "/nonexistent/x.pdb")
    assert str(e.value) == tcl_error("mol new /nonexistent/x.pdb type pdb waitfor all")
    assert isinstance(e.value, ValueError)
    with pytest.raises(TclError):
        molecule.load("psf", data("helix.psf"), "dcd", "/nonexistent/x.dcd")
    assert molecule.listall() == before
    with pytest.raises(ValueError):
        molecule.load("psf", data("helix.psf"), "dcd")


def test_new_and_rename():
    m = molecule.new("empty")
    assert molecule.name(m) == "empty" and molecule.numatoms(m) == 0
    n = molecule.new("blank", 5)
    assert molecule.numatoms(n) == int(tcl("molinfo %d get numatoms" % n)) == 5
    molecule.rename(n, "renamed")
    assert tcl("molinfo %d get name" % n) == "renamed"
    with pytest.raises(ValueError):
        molecule.new("bad", -1)


def test_read_counts_frames_like_mol_addfile():
    m = molecule.load("psf", data("helix.psf"))
    assert molecule.read(m, "dcd", data("helix.dcd"), beg=2, end=8, skip=3) == 3
    t = int(tcl("mol new %s" % data("helix.psf")))
    tcl("mol addfile %s first 2 last 8 step 3 waitfor all %d" % (data("helix.dcd"), t))
    assert molecule.numframes(m) == int(tcl("molinfo %d get numframes" % t)) == 3
    a = atomsel("all", m, 1).get("x")
    b = tcl_list("[atomselect %d all frame 1] get x" % t)
    assert a == pytest.approx([float(x) for x in b])
    with pytest.raises(TclError):
        molecule.read(m, "dcd", "/nonexistent.dcd")


def test_write_frames_and_selection(helix, tmp_path):
    out = str(tmp_path / "out.dcd")
    assert molecule.write(helix, "dcd", out, beg=1, end=4) == 4
    m = molecule.load("psf", data("helix.psf"), "dcd", out)
    assert molecule.numframes(m) == 4
    pdb = str(tmp_path / "ca.pdb")
    sel = atomsel("name CA", helix)
    assert molecule.write(helix, "pdb", pdb, beg=0, end=0, selection=sel) == 1
    ca = molecule.load("pdb", pdb)
    assert molecule.numatoms(ca) == len(sel) == int(tcl("[atomselect %d {name CA}] num" % helix))


def test_listall_exists_top_delete(helix):
    other = molecule.load("pdb", data("tiny.pdb"))
    assert molecule.listall() == [int(x) for x in tcl_list("molinfo list")]
    assert molecule.num() == int(tcl("molinfo num")) == 2
    assert molecule.exists(helix) == 1 and molecule.exists(999) == 0
    assert molecule.get_top() == other
    molecule.set_top(helix)
    assert int(tcl("molinfo top")) == helix
    molecule.delete(other)
    assert molecule.listall() == [helix]
    with pytest.raises(TclError) as e:
        molecule.numatoms(other)
    assert str(e.value) == tcl_error("molinfo %d get numatoms" % other)


def test_frames(helix):
    molecule.set_frame(helix, 4)
    assert molecule.get_frame(helix) == int(tcl("molinfo %d get frame" % helix)) == 4
    tcl("animate goto 2")
    assert molecule.get_frame(helix) == 2
    molecule.dupframe(helix, 0)
    assert molecule.numframes(helix) == 11
    molecule.delframe(helix, 0, 4)
    assert molecule.numframes(helix) == int(tcl("molinfo %d get numframes" % helix)) == 6


def test_visible_and_periodic(helix):
    molecule.set_visible(helix, False)
    assert tcl("molinfo %d get drawn" % helix) == "0" and not molecule.get_visible(helix)
    tcl("mol on %d" % helix)
    assert molecule.get_visible(helix)
    cell = molecule.get_periodic(helix, 0)
    assert cell["a"] == float(tcl("molinfo %d get a frame 0" % helix))
    assert set(cell) == {"a", "b", "c", "alpha", "beta", "gamma"}


def test_tcl_sees_python_and_python_sees_tcl():
    m = int(tcl("mol new %s" % data("tiny.pdb")))
    assert m in molecule.listall()
    p = molecule.new("from python")
    assert tcl_list("molinfo %d get name" % p) == ["from python"]
