"""test_modules.py: molrep, display, render, trans, animate, color, material, graphics,
label and evaltcl against the Tcl commands they wrap (the same values, the same image),
each change seen from Tcl."""
import os

import pytest

import molscope
from molscope import (molecule, molrep, display, render, trans, animate, color, material,
                      graphics, label, evaltcl, TclError)
from molscope._tcl import split
from conftest import data, tcl, tcl_list, tcl_error


def test_evaltcl():
    assert evaltcl("expr {6*7}") == "42"
    evaltcl("set ::py_var hello")
    assert tcl("set ::py_var") == "hello"
    with pytest.raises(TclError) as e:
        evaltcl("error {custom failure}")
    assert str(e.value) == "custom failure"


def test_molrep(helix):
    assert molrep.num(helix) == int(tcl("molinfo %d get numreps" % helix)) == 1
    r = molrep.addrep(helix, style="VDW 1.0 12.0", color="ResName", selection="name CA",
                      material="Glossy")
    assert r == 1 and molrep.num(helix) == 2
    assert molrep.get_style(helix, r) == tcl_list("molinfo %d get {{rep 1}}" % helix)[0]
    assert molrep.get_style(helix, r).startswith("VDW")
    assert molrep.get_selection(helix, r) == "name CA"
    assert molrep.get_color(helix, r) == tcl_list("molinfo %d get {{color 1}}" % helix)[0]
    assert molrep.get_material(helix, r) == "Glossy"
    molrep.modrep(helix, r, style="Lines")
    assert molrep.get_style(helix, r).startswith("Lines")
    name = molrep.get_repname(helix, r)
    assert molrep.repindex(helix, name) == r == int(tcl("mol repindex %d %s" % (helix, name)))
    molrep.set_visible(helix, r, False)
    assert not molrep.get_visible(helix, r) and tcl("mol showrep %d %d" % (helix, r)) == "0"
    molrep.delrep(helix, 0)
    assert molrep.num(helix) == 1
    with pytest.raises(TclError):
        molrep.addrep(helix, style="NoSuchStyle")
    assert molrep.num(helix) == 1


def test_display():
    display.set(projection="Orthographic")
    assert display.get("projection") == tcl("display get projection") == "Orthographic"
    display.set(projection="Perspective", nearclip=0.25)
    assert display.get("nearclip") == pytest.approx(float(tcl("display get nearclip")))
    assert display.get("nearclip") == pytest.approx(0.25)
    display.set(size=[320, 240])
    assert display.get("size") == [int(x) for x in split(tcl("display get size"))] == [320, 240]
    with pytest.raises(ValueError):
        display.get("nosuch")
    display.update()


def test_render_agrees_with_tcl(helix, tmp_path):
    assert render.listall() == tcl_list("render list")
    display.set(size=[64, 48])
    a, b = str(tmp_path / "py.ppm"), str(tmp_path / "tcl.ppm")
    render.render("TachyonInternal", a)
    tcl("render TachyonInternal %s" % b)
    with open(a, "rb") as fa, open(b, "rb") as fb:
        pa, pb = fa.read(), fb.read()
    assert pa == pb and len(pa) > 64 * 48 * 3
    with pytest.raises(TclError):
        render.render("NoSuchRenderer", a)


def test_trans(helix):
    trans.resetview(helix)
    trans.rotate("y", 90)
    rot = trans.get_rotation(helix)
    assert rot[0][2] == pytest.approx(1.0, abs=1e-5) or rot[0][2] == pytest.approx(-1.0, abs=1e-5)
    assert rot == [[float(x) for x in split(r)] for r in
                   split(tcl_list("molinfo %d get rotate_matrix" % helix)[0])]
    trans.set_center(helix, (1, 2, 3))
    assert trans.get_center(helix) == pytest.approx((1, 2, 3))
    s0 = trans.get_scale(helix)
    trans.scale(2)
    assert trans.get_scale(helix) == pytest.approx(2 * s0)
    trans.fix(helix, True)
    assert trans.is_fixed(helix) and tcl("molinfo %d get fixed" % helix) == "1"
    trans.show(helix, False)
    assert not trans.is_shown(helix)
    trans.translate(1, 0, 0)


def test_animate(helix):
    animate.goto(3)
    assert molecule.get_frame(helix) == 3
    animate.next()
    assert int(tcl("molinfo %d get frame" % helix)) == 4
    animate.prev()
    assert molecule.get_frame(helix) == 3
    animate.rock()
    assert animate.style() == tcl("animate style") == "Rock"
    animate.once()
    assert animate.speed(0.5) == pytest.approx(float(tcl("animate speed")))
    assert animate.skip(2) == int(tcl("animate skip")) == 2
    animate.skip(1)
    animate.activate(helix, False)
    assert not animate.is_active(helix) and tcl("molinfo %d get active" % helix) == "0"
    animate.activate(helix, True)


def test_color():
    assert color.categories() == tcl_list("colorinfo categories")
    disp = color.get_colormap("Display")
    assert disp["Background"] == tcl("colorinfo category Display Background")
    color.set_colormap("Display", {"Background": "white"})
    assert tcl("colorinfo category Display Background") == "white"
    color.set_colormap("Display", disp)
    colors = color.get_colors()
    assert colors["red"] == tuple(float(x) for x in tcl_list("colorinfo rgb red"))
    color.set_colorid("red", (0.9, 0.1, 0.1))
    assert [float(x) for x in tcl_list("colorinfo rgb red")] == pytest.approx([0.9, 0.1, 0.1])
    color.set_colorid("red", colors["red"])
    assert len(color.get_colorlist()) == int(tcl("colorinfo max"))
    color.set_scale(method="BWR", midpoint=0.4)
    assert color.scale_method() == tcl("colorinfo scale method") == "BWR"
    assert color.scale_midpoint() == pytest.approx(0.4)
    assert color.scale_methods() == tcl_list("colorinfo scale methods")
    color.set_scale(method="RWB", midpoint=0.5)


def test_material():
    assert material.listall() == tcl_list("material list")
    s = material.settings("Opaque")
    assert list(s.values()) == [float(x) for x in tcl_list("material settings Opaque")]
    assert s["diffuse"] == pytest.approx(0.65)
    name = material.add("PyMat", copy="Opaque")
    assert name == "PyMat" and "PyMat" in material.listall()
    material.change("PyMat", opacity=0.5, shininess=0.9)
    assert material.settings("PyMat")["opacity"] == pytest.approx(0.5)
    material.rename("PyMat", "PyMat2")
    assert "PyMat2" in tcl_list("material list")
    material.delete("PyMat2")
    assert "PyMat2" not in material.listall()
    with pytest.raises(ValueError):
        material.change("Opaque", nosuch=1)
    with pytest.raises(TclError):
        material.settings("NoSuchMaterial")


def test_graphics(helix):
    g = graphics.sphere(helix, (0, 0, 0), radius=2)
    assert graphics.info(helix, g) == tcl("graphics %d info %d" % (helix, g))
    assert graphics.info(helix, g).startswith("sphere")
    c = graphics.cylinder(helix, (0, 0, 0), (1, 1, 1), radius=0.5, filled=True)
    t = graphics.text(helix, (1, 2, 3), "hello world")
    graphics.color(helix, "red")
    assert graphics.listall(helix) == [int(x) for x in tcl_list("graphics %d list" % helix)]
    assert {g, c, t} <= set(graphics.listall(helix))
    graphics.delete(helix, g)
    assert g not in graphics.listall(helix)
    graphics.delete(helix, "all")
    assert graphics.listall(helix) == []


def test_label(helix):
    i = label.add(label.ATOM, [helix], [1])
    assert label.listall(label.ATOM) == tcl_list("label list Atoms")
    assert len(label.listall(label.ATOM)) == 1
    b = label.add(label.BOND, [helix, helix], [0, 1])
    vals = label.get_values(label.BOND, b)
    assert len(vals) == molecule.numframes(helix)
    assert vals == pytest.approx([float(x) for x in tcl_list("label graph Bonds %d" % b)])
    label.delete(label.ATOM, i)
    assert label.listall(label.ATOM) == []
    with pytest.raises(ValueError):
        label.add(label.BOND, [helix], [0, 1])
    assert label.textsize(1.5) == pytest.approx(float(tcl("label textsize")))
