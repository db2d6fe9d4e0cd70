"""test_notebook.py: the notebook additions of the molscope package. molscope.render: the
image in memory (numpy RGBA, PNG bytes, _repr_png_) equals the file `render TachyonInternal`
writes for the same scene, sizes and sample counts hold for that image only, a path writes
the file as `render` does, errors are TclError with the Tcl command's message. molscope.live:
the live view's HTML iframe holds the tokened loopback URL, which answers 200 and the page
(403 without the token), both from a script (serve) and from a running asyncio loop as
Jupyter's kernel has one."""
import asyncio
import io
import os
import threading
import urllib.error
import urllib.parse
import urllib.request

import numpy
import pytest
from PIL import Image as PILImage

import molscope
from molscope import display, render, TclError
from conftest import tcl, tcl_error


def pixels(path_or_bytes):
    src = io.BytesIO(path_or_bytes) if isinstance(path_or_bytes, bytes) else path_or_bytes
    with PILImage.open(src) as im:
        return numpy.asarray(im.convert("RGB"))


def test_render_equals_tcl_render(helix, tmp_path):
    display.set(size=[96, 72])
    ref = str(tmp_path / "tcl.ppm")
    tcl("render TachyonInternal %s" % ref)
    img = molscope.render()
    assert (img.width, img.height) == (96, 72)
    a = img.array
    assert a.shape == (72, 96, 4) and a.dtype == numpy.uint8
    assert (a[:, :, 3] == 255).all()
    assert numpy.array_equal(a[:, :, :3], pixels(ref))
    assert numpy.array_equal(pixels(img.png), pixels(ref))
    assert img.png.startswith(b"\x89PNG") and img._repr_png_() == img.png
    # the molecule is in it: a fair share of pixels differs from the background
    bg = a[0, 0, :3]
    assert (a[:, :, :3] != bg).any(axis=2).mean() > 0.02


def test_render_size_is_for_that_image_only(helix, tmp_path):
    display.set(size=[50, 40])
    for w, h in ((64, 48), (33, 17), (120, 30)):
        img = molscope.render(size=(w, h))
        assert img.array.shape == (h, w, 4) and (img.width, img.height) == (w, h)
        assert pixels(img.png).shape == (h, w, 3)
    assert tcl("display get size") == "50 40"
    tcl("display resize 64 48")
    ref = str(tmp_path / "ref.ppm")
    tcl("render TachyonInternal %s" % ref)
    tcl("display resize 50 40")
    assert numpy.array_equal(molscope.render(size=(64, 48)).array[:, :, :3], pixels(ref))


def test_render_samples_for_that_image_only(helix, tmp_path):
    display.set(size=[40, 30])
    tcl("render aasamples TachyonInternal 2")
    ref = str(tmp_path / "ref.ppm")
    tcl("render TachyonInternal %s" % ref)
    tcl("render aasamples TachyonInternal 7")
    img = molscope.render(aasamples=2)
    assert numpy.array_equal(img.array[:, :, :3], pixels(ref))
    assert tcl("render aasamples TachyonInternal") == "7"


def test_render_path_writes_the_file(helix, tmp_path):
    display.set(size=[48, 36])
    png, tga = tmp_path / "out.png", tmp_path / "out.tga"
    img = molscope.render(str(png))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert numpy.array_equal(pixels(str(png)), img.array[:, :, :3])
    molscope.render(tga)            # a path object; TGA as `render` writes it
    ref = tmp_path / "ref.tga"
    tcl("render TachyonInternal %s" % ref)
    assert tga.read_bytes() == ref.read_bytes()
    img.save(str(tmp_path / "saved.png"))
    assert (tmp_path / "saved.png").read_bytes() == img.png


def test_render_errors_carry_tcl_messages(helix, tmp_path):
    display.set(size=[40, 30])
    with pytest.raises(TclError) as e:
        molscope.render(method="NoSuchRenderer")
    assert str(e.value) == tcl_error("render NoSuchRenderer %s/x.png" % tmp_path)
    bad = "/nonexistent-dir/x.png"
    with pytest.raises(TclError) as e:
        molscope.render(bad)
    assert str(e.value) == tcl_error("render TachyonInternal %s" % bad)
    with pytest.raises(TclError) as e:
        molscope.render(method="POV3")
    assert "POV3 writes a scene file, not an image" in str(e.value)
    with pytest.raises(TclError) as e:
        molscope.render(size=(0, 10))
    assert str(e.value) == tcl_error("display resize 0 10")
    with pytest.raises(ValueError):
        molscope.render(size="big")
    with pytest.raises(TclError) as e:
        molscope.render(aasamples=-3)
    assert str(e.value) == tcl_error("render aasamples TachyonInternal -3")
    assert tcl("display get size") == "40 30"
    assert list(tmp_path.iterdir()) == []


def test_render_module_keeps_vmd_functions(helix, tmp_path):
    assert callable(render) and render.listall() == molscope._tcl.split(tcl("render list"))
    display.set(size=[32, 24])
    f = str(tmp_path / "v.ppm")
    render.render("TachyonInternal", f)
    assert numpy.array_equal(pixels(f), render(size=(32, 24)).array[:, :, :3])


def fetch(url):
    """(status, body) of a GET; an HTTP error's status too."""
    try:
        with urllib.request.urlopen(url, timeout=20) as r:
            return r.status, r.read().decode("utf-8", "replace")
    except urllib.error.HTTPError as e:
        return e.code, ""


def without_token(url):
    return url.split("?")[0]


@pytest.fixture
def live_view():
    view = molscope.live()
    yield view
    view.stop()


def test_live_html_and_token(helix, live_view):
    v = live_view
    parts = urllib.parse.urlsplit(v.url)
    assert parts.hostname == "127.0.0.1" and parts.port == v.port
    assert len(v.token) == 32 and v.url.endswith("token=" + v.token)
    html = v._repr_html_()
    assert html.startswith("<iframe") and 'src="%s"' % v.url in html
    assert v.url in tcl("display live status")
    assert molscope.live().url == v.url        # the running server, not a second one
    results = {}

    def client():
        results["page"] = fetch(v.url)
        results["none"] = fetch(without_token(v.url))
        results["wrong"] = fetch(without_token(v.url) + "?token=" + "0" * 32)

    t = threading.Thread(target=client)
    t.start()
    while t.is_alive():
        v.serve(0.05)
    status, body = results["page"]
    assert status == 200 and "<html" in body.lower()
    assert results["none"][0] == 403 and results["wrong"][0] == 403


def test_live_stop_closes_the_port(helix):
    v = molscope.live()
    assert v.running
    v.stop()
    assert not v.running and tcl("display live status") == "off"
    with pytest.raises(urllib.error.URLError):
        urllib.request.urlopen(v.url, timeout=5)
    v.stop()                                   # twice is harmless


def test_live_answers_from_a_running_asyncio_loop(helix):
    """As in Jupyter: nothing calls serve; the kernel's loop runs molscope's events."""
    async def main():
        v = molscope.live()
        try:
            loop = asyncio.get_running_loop()
            return await loop.run_in_executor(None, fetch, v.url)
        finally:
            v.stop()

    status, body = asyncio.run(main())
    assert status == 200 and "<html" in body.lower()
