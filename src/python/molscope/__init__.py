"""molscope: VMD's Python API over molscope's Tcl commands.

Inside molscope (gopython, molscope -python) the modules are also importable under VMD's
names (`import vmd`, `from vmd import molecule, atomsel, ...`). From a plain python3,
`import molscope` loads the _molscope extension, which makes a molscope application (the
molecules, the scene, a Tcl interpreter running every molscope command) in this process.
doc/python.md lists the API and how it differs from VMD's."""
import os as _os

import _molscope


def _anchor():
    """Where a molscope program would be, for finding the Tcl library and the plugins:
    the build tree's src/molscope beside src/python/.libs, else <prefix>/bin/molscope
    beside <prefix>/lib/python3.X/dist-packages."""
    here = _os.path.dirname(_os.path.realpath(_molscope.__file__))
    if _os.path.basename(here) == ".libs":
        return _os.path.normpath(_os.path.join(here, "..", "..", "molscope"))
    return _os.path.normpath(_os.path.join(here, "..", "..", "..", "bin", "molscope"))


if not _molscope.embedded:
    _molscope.start(_anchor())

from ._tcl import TclError  # noqa: E402
from . import molecule, molrep, display, render, trans, animate  # noqa: E402
from . import color, material, graphics, label  # noqa: E402
try:
    from . import vmdnumpy  # noqa: E402  (needs numpy)
except ImportError:
    pass
from ._atomsel import atomsel  # noqa: E402
from . import measure, topology, selection, axes  # noqa: E402
from ._image import Image  # noqa: E402
from ._live import live, LiveView  # noqa: E402


def evaltcl(script):
    """Evaluate Tcl text on molscope's interpreter; its result as a string. A Tcl error
    raises TclError with Tcl's message."""
    return _molscope.evaltcl(script)


__all__ = ["molecule", "atomsel", "molrep", "display", "render", "trans", "animate",
           "color", "material", "graphics", "label", "measure", "topology", "selection",
           "axes", "evaltcl", "TclError", "Image", "live", "LiveView"]
