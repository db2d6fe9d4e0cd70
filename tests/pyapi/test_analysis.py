"""test_analysis.py: VMD's Python modules measure, topology, selection and axes against the
Tcl commands they wrap (measure, topotools' topo, atomselect macro, axes): the same values,
changes seen from Tcl, errors as TclError with Tcl's message."""
import pytest

from molscope import atomsel, measure, topology, selection, axes, molecule, TclError
from conftest import data, tcl, tcl_list, tcl_error


def tcl_floats(script):
    return [float(x) for x in tcl_list(script)]


def test_measure_bond_angle_dihedral(helix):
    assert measure.bond(0, 1, helix) == pytest.approx(tcl_floats("measure bond {0 1} molid %d" % helix))
    assert len(measure.bond(0, 1)) == 1          # the top molecule, its current frame
    assert measure.bond(0, 4, helix, frame=3) == pytest.approx(
        tcl_floats("measure bond {0 4} molid %d frame 3" % helix))
    allf = measure.bond(0, 4, helix, first=0)
    assert len(allf) == molecule.numframes(helix) == 10
    assert allf == pytest.approx(tcl_floats("measure bond {0 4} molid %d frame all" % helix))
    assert measure.bond(0, 4, helix, first=2, last=5) == pytest.approx(allf[2:6])
    assert measure.angle(0, 1, 4, helix, frame=2) == pytest.approx(
        tcl_floats("measure angle {0 1 4} molid %d frame 2" % helix))
    d = measure.dihedral(0, 1, 4, 6, helix, first=0)
    assert d == pytest.approx(tcl_floats("measure dihed {0 1 4 6} molid %d frame all" % helix))
    assert all(-180 <= x <= 180 for x in d)
    assert measure.imprp(0, 1, 4, 6, helix) == pytest.approx(
        tcl_floats("measure imprp {0 1 4 6} molid %d" % helix))


def test_measure_across_molecules(helix):
    other = molecule.load("pdb", data("tiny.pdb"))
    got = measure.bond(0, 0, helix, molid2=other)
    assert got == pytest.approx(tcl_floats("measure bond {{0 %d} {0 %d}} molid %d"
                                           % (helix, other, helix)))


def test_measure_errors(helix):
    with pytest.raises(TclError) as e:
        measure.bond(0, 99999, helix)
    assert str(e.value) == tcl_error("measure bond {{0 %d} {99999 %d}} molid %d"
                                     % (helix, helix, helix))
    with pytest.raises(TclError):
        measure.angle(0, 1, 2, molid=4242)


def test_measure_selection_functions(helix):
    a, b = atomsel("name CA", helix, 0), atomsel("name CA", helix, 5)
    tcl("set ::A [atomselect %d {name CA} frame 0]; set ::B [atomselect %d {name CA} frame 5]"
        % (helix, helix))
    assert measure.center(a) == pytest.approx(tcl_floats("measure center $::A"))
    assert measure.center(a, weight="mass") == pytest.approx(
        tcl_floats("measure center $::A weight mass"))
    assert measure.rmsd(a, b) == pytest.approx(float(tcl("measure rmsd $::A $::B")))
    assert len(measure.fit(a, b)) == 16
    assert measure.rgyr(a) == pytest.approx(float(tcl("measure rgyr $::A")))
    lo, hi = measure.minmax(a)
    assert list(lo) + list(hi) == pytest.approx(
        [float(x) for v in tcl_list("measure minmax $::A") for x in v.split()])
    assert measure.sasa(1.4, a) == pytest.approx(float(tcl("measure sasa 1.4 $::A")))
    heavy = atomsel("noh", helix)
    tcl("set ::H [atomselect %d noh]" % helix)
    c = measure.contacts(2.0, heavy)
    assert [len(c[0]), len(c[1])] == [len(x.split()) for x in tcl_list("measure contacts 2.0 $::H")]
    assert c[0] and len(c[0]) == len(c[1])
    hb = measure.hbonds(3.5, 40, atomsel("all", helix))
    assert [len(x) for x in hb] == [len(x.split()) for x in
                                    tcl_list("measure hbonds 3.5 40 [atomselect %d all]" % helix)]
    assert len(measure.rmsf(a, 0, 9)) == len(a)


def test_topology_bonds(helix):
    tcl("package require topotools")
    ref = [tuple(int(x) for x in b.split()) for b in tcl_list("topo -molid %d getbondlist" % helix)]
    assert topology.bonds(helix) == ref and len(ref) > 0
    typed = topology.bonds(helix, type=True, order=True)
    assert [t[:2] for t in typed] == ref and all(len(t) == 4 for t in typed)
    assert typed[0][3] == 1.0
    n = int(tcl("topo -molid %d numbonds" % helix))
    topology.addbond(0, 9, helix, order=2.0, type="xx")
    assert int(tcl("topo -molid %d numbonds" % helix)) == n + 1
    assert "{0 9 xx 2.0}" in tcl("topo -molid %d getbondlist both" % helix)
    assert "xx" in topology.bondtypes(helix) == tcl_list("topo -molid %d bondtypenames" % helix)
    topology.delbond(0, 9, helix)
    assert int(tcl("topo -molid %d numbonds" % helix)) == n
    assert topology.del_all_bonds(helix) == n
    assert topology.bonds(helix) == [] and tcl("topo -molid %d numbonds" % helix) == "0"


def test_topology_terms(helix):
    tcl("package require topotools")
    topology.addangle(0, 1, 4, helix, type="HCC")
    topology.addangle(1, 4, 5, helix)
    assert topology.angles(helix) == [(0, 1, 4), (1, 4, 5)]
    assert topology.angles(helix, type=True)[0] == (0, 1, 4, "HCC")
    assert tcl_list("topo -molid %d getanglelist" % helix)[0].split() == ["HCC", "0", "1", "4"]
    assert topology.angletypes(helix) == tcl_list("topo -molid %d angletypenames" % helix)
    topology.adddihedral(0, 1, 4, 6, helix, type="D")
    topology.addimproper(1, 0, 4, 2, helix)
    assert topology.dihedrals(helix, type=True) == [(0, 1, 4, 6, "D")]
    assert topology.impropers(helix) == [(1, 0, 4, 2)]
    assert topology.dihedraltypes(helix) == ["D"]
    assert topology.impropertypes(helix) == tcl_list("topo -molid %d impropertypenames" % helix)
    topology.delangle(0, 1, 4, helix)
    assert topology.angles(helix) == [(1, 4, 5)]
    topology.deldihedral(0, 1, 4, 6, helix)
    topology.delimproper(1, 0, 4, 2, helix)
    assert topology.dihedrals(helix) == [] == topology.impropers(helix)
    assert topology.del_all_angles(helix) == 1 and topology.angles(helix) == []
    assert topology.del_all_dihedrals(helix) == 0 == topology.del_all_impropers(helix)


def test_topology_errors(helix):
    with pytest.raises(TclError) as e:
        topology.bonds(4242)
    assert str(e.value) == tcl_error("topo -molid 4242 getbondlist none")
    with pytest.raises(TclError):
        topology.addbond(0, 999999, helix)


def test_selection_macros(helix):
    selection.add_macro("pyca", "name CA and resid 1 to 3")
    assert selection.get_macro("pyca") == tcl("atomselect macro pyca")
    assert "pyca" in selection.all_macros()
    assert selection.all_macros() == tcl_list("atomselect macro")
    assert len(atomsel("pyca", helix)) == int(tcl("[atomselect %d pyca] num" % helix)) > 0
    selection.del_macro("pyca")
    assert "pyca" not in tcl_list("atomselect macro")
    with pytest.raises(TclError) as e:
        selection.get_macro("pyca")
    assert str(e.value) == tcl_error("atomselect macro pyca")


def test_axes():
    old = axes.get_location()
    try:
        axes.set_location(axes.ORIGIN)
        assert axes.get_location() == tcl("axes location") == "Origin"
        assert axes.get_location() in axes.get_locations()
        with pytest.raises(TclError) as e:
            axes.set_location("Nowhere")
        assert str(e.value) == tcl_error("axes location Nowhere")
    finally:
        axes.set_location(old)
