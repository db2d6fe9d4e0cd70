"""test_atomsel.py: molscope.atomsel against atomselect and measure: the same atoms,
values, centres, RMSDs, fits, bounds, areas, contacts, hydrogen bonds and bonds; moves
seen from Tcl; errors with Tcl's messages."""
import numpy as np
import pytest

from molscope import atomsel, molecule, TclError
from conftest import data, tcl, tcl_list, tcl_error


def floats(words):
    return [float(w) for w in words]


def sel_tcl(helix, text, frame=0):
    name = tcl("atomselect %d {%s} frame %d" % (helix, text, frame))
    return name


def test_len_iter_contains(helix):
    s = atomsel("name CA", helix)
    t = sel_tcl(helix, "name CA")
    assert len(s) == int(tcl(t + " num")) == 23
    assert list(s) == [int(i) for i in tcl_list(t + " list")]
    assert 8 in s and 0 not in s
    assert s.molid == helix and s.text == "name CA"


def test_defaults_are_top_and_current_frame(helix):
    molecule.set_frame(helix, 3)
    s = atomsel()
    assert s.molid == helix and len(s) == 392 and s.frame == -1
    assert s.get("x") == pytest.approx(floats(tcl_list(sel_tcl(helix, "all", 3) + " get x")))
    molecule.set_frame(helix, 6)
    assert s.get("x") == pytest.approx(floats(tcl_list(sel_tcl(helix, "all", 6) + " get x")))


def test_get_any_keyword(helix):
    s = atomsel("resid 1 to 3", helix, 0)
    t = sel_tcl(helix, "resid 1 to 3")
    for kw in ("name", "resname", "segname", "type"):
        assert s.get(kw) == [w if not w.isdigit() else int(w) for w in tcl_list(t + " get " + kw)]
    for kw in ("x", "y", "z", "mass", "charge", "beta"):
        assert s.get(kw) == pytest.approx(floats(tcl_list(t + " get " + kw)))
    assert s.get("resid") == [int(w) for w in tcl_list(t + " get resid")]


def test_set_one_value_and_per_atom(helix):
    s = atomsel("name CA", helix)
    s.set("beta", 2.5)
    assert floats(tcl_list("[atomselect %d {name CA}] get beta" % helix)) == [2.5] * len(s)
    s.set("occupancy", list(range(len(s))))
    assert floats(tcl_list("[atomselect %d {name CA}] get occupancy" % helix)) == \
        list(range(len(s)))
    s.set("segname", "PYT")
    assert tcl_list("[atomselect %d {name CA}] get segname" % helix) == ["PYT"] * len(s)
    s.set("user", np.arange(len(s), dtype=np.float32) / 2)
    assert floats(tcl_list("[atomselect %d {name CA}] get user" % helix))[:3] == [0, 0.5, 1.0]
    s.set("name", "C{A")      # no quoting problem: the words go over as a list
    assert s.get("name") == ["C{A"] * len(s)
    with pytest.raises(TclError) as e:
        s.set("beta", [1, 2])
    assert "atomselect" in str(e.value) or "set" in str(e.value)


def test_frame_property_and_update(helix):
    s = atomsel("index 0", helix, frame=0)
    x0 = s.get("x")
    s.frame = 5
    assert s.frame == 5
    assert s.get("x") == pytest.approx(floats(tcl_list(sel_tcl(helix, "index 0", 5) + " get x")))
    assert s.get("x") != x0
    d = atomsel("x > 0", helix, frame=0)
    n = len(d)
    atomsel("all", helix, 0).moveby((-100, 0, 0))
    d.update()
    assert len(d) == 0 and n > 0


def test_center_rmsd_fit_rgyr(helix):
    s = atomsel("name CA", helix, 0)
    r = atomsel("name CA", helix, 5)
    t, u = sel_tcl(helix, "name CA", 0), sel_tcl(helix, "name CA", 5)
    assert s.center() == pytest.approx(floats(tcl_list("measure center " + t)))
    assert s.center("mass") == pytest.approx(floats(tcl_list("measure center %s weight mass" % t)))
    assert s.rmsd(r) == pytest.approx(float(tcl("measure rmsd %s %s" % (t, u))))
    assert s.rgyr() == pytest.approx(float(tcl("measure rgyr " + t)))
    rows = [floats(tcl_list("lindex {%s} %d" % (tcl("measure fit %s %s" % (t, u)), i)))
            for i in range(4)]
    m = s.fit(r)
    assert len(m) == 16
    assert [m[c * 4 + k] for k in range(4) for c in range(4)] == \
        pytest.approx([rows[k][c] for k in range(4) for c in range(4)])
    before = s.rmsd(r)
    atomsel("all", helix, 0).move(m)
    after = s.rmsd(r)
    assert after < before
    assert after == pytest.approx(float(tcl("measure rmsd %s %s" % (t, u))))
    with pytest.raises(TclError):
        s.rmsd(atomsel("name CB", helix))


def test_moveby_seen_from_tcl(helix):
    s = atomsel("all", helix, 0)
    c0 = s.center()
    s.moveby((1, 2, 3))
    c1 = floats(tcl_list("measure center [atomselect %d all frame 0]" % helix))
    assert c1 == pytest.approx([c0[0] + 1, c0[1] + 2, c0[2] + 3], abs=1e-4)
    with pytest.raises(ValueError):
        s.move([1, 0, 0])


def test_minmax(helix):
    s = atomsel("protein", helix, 0)
    t = sel_tcl(helix, "protein")
    lo, hi = s.minmax()
    tl, th = tcl_list("measure minmax " + t)
    assert list(lo) == pytest.approx(floats(tcl_list("list " + tl)))
    assert list(hi) == pytest.approx(floats(tcl_list("list " + th)))
    rlo, rhi = s.minmax(radii=True)
    assert rlo[0] < lo[0] and rhi[0] > hi[0]


def test_sasa(helix):
    s = atomsel("protein", helix, 0)
    t = sel_tcl(helix, "protein")
    assert s.sasa(1.4) == pytest.approx(float(tcl("measure sasa 1.4 " + t)), rel=1e-6)
    area, pts = s.sasa(1.4, points=True)
    assert area == pytest.approx(s.sasa(1.4)) and len(pts) > 0 and len(pts[0]) == 3
    ca = atomsel("name CA", helix, 0)
    assert s.sasa(1.4, restrict=ca) == pytest.approx(
        float(tcl("measure sasa 1.4 %s -restrict %s" % (t, sel_tcl(helix, "name CA")))))


def test_contacts_and_hbonds(helix):
    s = atomsel("name CA", helix, 0)
    t = sel_tcl(helix, "name CA")
    other = atomsel("name CA", helix, 0)
    got = s.contacts(other, 4.0)
    want = [[int(i) for i in tcl_list("list " + w)] for w in tcl_list("measure contacts 4 " + t)]
    assert got == want and len(got[0]) > 0
    p = atomsel("protein", helix, 0)
    hb = p.hbonds(3.5, 40)
    want = [[int(i) for i in tcl_list("list " + w)]
            for w in tcl_list("measure hbonds 3.5 40 " + sel_tcl(helix, "protein"))]
    assert hb == want and len(hb) == 3 and len(hb[0]) > 0


def test_bonds_get_and_set(helix):
    s = atomsel("index 0 to 3", helix)
    t = sel_tcl(helix, "index 0 to 3")
    assert s.bonds == [[int(i) for i in tcl_list("list " + b)] for b in tcl_list(t + " getbonds")]
    s.bonds = [[1], [0], [], []]
    assert tcl_list(t + " getbonds") == ["1", "0", "", ""]


def test_write(helix, tmp_path):
    path = str(tmp_path / "ca.pdb")
    atomsel("name CA", helix).write("pdb", path)
    assert molecule.numatoms(molecule.load("pdb", path)) == 23


def test_bad_selection_is_tcl_error(helix):
    with pytest.raises(TclError) as e:
        atomsel("nonsense_kw 1", helix)
    assert str(e.value) == tcl_error("atomselect %d {nonsense_kw 1}" % helix)
    with pytest.raises(TclError):
        atomsel("all", 12345)
