"""render: VMD's Python `render` module (the render methods, rendering to a file) that is
also callable: `molscope.render(path=None, method="TachyonInternal", size=(w, h), ...)`
returns the image in memory (_image.py), since VMD's module name and the Pythonic function
share the name `render`."""
import sys as _sys
import types as _types

from ._tcl import call_list, call
from . import _image


def listall():
    return call_list("render", "list")


def render(method, filename):
    call("render", method, filename)


class _CallableModule(_types.ModuleType):
    def __call__(self, path=None, method="TachyonInternal", size=None, aasamples=None,
                 aosamples=None):
        return _image.render(path, method, size, aasamples, aosamples)


_CallableModule.__call__.__doc__ = _image.render.__doc__
_sys.modules[__name__].__class__ = _CallableModule
