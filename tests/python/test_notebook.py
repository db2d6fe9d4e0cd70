"""test_notebook.py: executes doc/analysis.ipynb headlessly (Debian's python3-nbclient and
python3-ipykernel, the python3 kernel) on molscope's build-tree module, and checks what a
reader sees: every cell ran, the inline render (molscope.render) is a PNG of the size asked
that shows the molecule (a fair share of pixels differs from the background), the RMSD plot
is an image, the live view cell shows an iframe on a tokened loopback URL, and (a cell the
test inserts) the kernel's event loop answers a GET of that URL with 200, and 403 without
the token. Skipped with the reason when Python was not built (a Tcl-only build) or, except
under CI=true, when the notebook packages are missing."""
import io
import os
import re
import sys
import base64

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mstest import Reporter, dirs  # noqa: E402

R = Reporter("notebook")
NEEDED = [("nbclient", "python3-nbclient"), ("nbformat", "python3-nbformat"),
          ("ipykernel", "python3-ipykernel"), ("matplotlib", "python3-matplotlib"),
          ("PIL", "python3-pil"), ("numpy", "python3-numpy")]


def missing():
    """The notebook packages missing here, or None."""
    import importlib
    for mod, pkg in NEEDED:
        try:
            importlib.import_module(mod)
        except ImportError:
            return "%s is not installed (scripts/bootstrap --test)" % pkg
    return None


def images(nb, mime="image/png"):
    """The decoded images of every output of every code cell, in order."""
    return [base64.b64decode(o["data"][mime]) for c in nb.cells if c.cell_type == "code"
            for o in c.get("outputs", []) if mime in o.get("data", {})]


def htmls(nb):
    return [o["data"]["text/html"] for c in nb.cells if c.cell_type == "code"
            for o in c.get("outputs", []) if "text/html" in o.get("data", {})]


def shows_molecule(png, size):
    from PIL import Image
    import numpy
    with Image.open(io.BytesIO(png)) as im:
        a = numpy.asarray(im.convert("RGB"))
    if (a.shape[1], a.shape[0]) != size:
        return "size %dx%d, not %dx%d" % (a.shape[1], a.shape[0], size[0], size[1])
    share = (a != a[0, 0]).any(axis=2).mean()
    return None if share > 0.03 else "%.1f%% of the pixels differ from the background" % (100 * share)


# Inserted after the live view's cell (not part of the example): while the kernel awaits,
# its event loop serves the page, as it does for a browser while the notebook is idle.
PROBE = """import asyncio, urllib.error, urllib.request
def _status(url):
    try:
        return urllib.request.urlopen(url, timeout=20).status
    except urllib.error.HTTPError as e:
        return e.code
_loop = asyncio.get_running_loop()
print("live page", await _loop.run_in_executor(None, _status, view.url),
      await _loop.run_in_executor(None, _status, view.url.split("?")[0]))"""


def with_probe(nb):
    """The notebook with PROBE after the cell that starts the live view; its index."""
    import nbformat
    i = next(k for k, c in enumerate(nb.cells) if c.cell_type == "code" and "molscope.live()" in c.source) + 1
    nb.cells.insert(i, nbformat.v4.new_code_cell(PROBE))
    return i


def run(path):
    import nbclient
    import nbformat
    srcdir, builddir, data, _ = dirs()
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [os.path.join(builddir, "src", "python"), os.environ.get("PYTHONPATH", "")])
    os.environ["MS_TEST_DATA"] = os.path.abspath(data)
    nb = nbformat.read(path, as_version=4)
    nb.probe = with_probe(nb)
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": os.path.dirname(path)}})
    try:
        client.execute()
    except Exception as e:                 # a cell failed: its error is the message
        R.report(False, "every cell runs", str(e).strip().splitlines()[-1][:300])
        return nb
    R.report(True, "every cell runs")
    return nb


def main():
    if not os.path.exists(os.path.join(dirs()[1], "src", "python", "_molscope.so")):
        R.skip("analysis.ipynb", "molscope was configured without Python (--without-python "
               "or no libpython3-dev)")
        return 0
    why = missing()
    if why:
        if os.environ.get("CI") == "true":
            R.report(False, "analysis.ipynb", "cannot run under CI: " + why)
            return 1
        R.skip("analysis.ipynb", why)
        return 0
    srcdir = dirs()[0]
    nb = run(os.path.join(srcdir, "doc", "analysis.ipynb"))
    pngs = images(nb)
    R.report(len(pngs) == 2, "two image outputs (the render, the RMSD plot)", "%d" % len(pngs))
    if pngs:
        bad = shows_molecule(pngs[0], (360, 270))
        R.report(bad is None, "the inline render shows the molecule", bad or "")
    if len(pngs) > 1:
        R.report(len(pngs[1]) > 2000 and pngs[1].startswith(b"\x89PNG"), "the RMSD plot is an image")
    frames = [h for h in htmls(nb) if h.startswith("<iframe")]
    ok = len(frames) == 1 and re.search(r'src="http://127\.0\.0\.1:\d+/\?token=[0-9a-f]{32}"',
                                        frames[0])
    R.report(bool(ok), "the live view is an iframe on its tokened loopback URL", str(frames)[:200])
    said = "".join(o.get("text", "") for o in nb.cells[nb.probe].get("outputs", []))
    R.report("live page 200 403" in said,
             "the kernel serves the live page (200 with the token, 403 without)", said[:200])
    return 1 if R.failures else 0


if __name__ == "__main__":
    sys.exit(main())
