"""_image.py: molscope.render, the Pythonic rendering VMD's module lacks: the scene rendered in
memory by one of molscope's image devices (the same C code as the `render` command, through
_molscope.render_image) as an Image: its pixels as a numpy RGBA array, its PNG bytes, and
_repr_png_ so that Jupyter shows it inline."""
import os

import _molscope

from ._tcl import call, split, TclError


class Image:
    """A rendered image: width, height, png (bytes), array (numpy, height x width x 4, uint8,
    alpha 255), save(path)."""

    def __init__(self, width, height, rgb, png):
        self.width = width
        self.height = height
        self._rgb = rgb
        self.png = png

    @property
    def array(self):
        import numpy
        rgb = numpy.frombuffer(self._rgb, dtype=numpy.uint8).reshape(self.height, self.width, 3)
        rgba = numpy.empty((self.height, self.width, 4), dtype=numpy.uint8)
        rgba[:, :, :3] = rgb
        rgba[:, :, 3] = 255
        return rgba

    def save(self, path):
        """Write the PNG bytes to path."""
        with open(path, "wb") as f:
            f.write(self.png)

    def _repr_png_(self):
        return self.png

    def __repr__(self):
        return "<molscope.Image %dx%d, %d bytes of PNG>" % (self.width, self.height, len(self.png))


def _size(size):
    try:
        w, h = (int(x) for x in size)
    except (TypeError, ValueError):
        raise ValueError("render: size must be (width, height), got %r" % (size,)) from None
    return w, h


class _Setting:
    """A setting changed for one render and put back after it, whatever happens."""

    def __init__(self, get, set_, value):
        self.get, self.set, self.value = get, set_, value

    def __enter__(self):
        self.old = self.get() if self.value is not None else None
        if self.value is not None:
            self.set(self.value)

    def __exit__(self, *exc):
        if self.old is not None:
            self.set(self.old)


def render(path=None, method="TachyonInternal", size=None, aasamples=None, aosamples=None):
    """Render the current scene with an image device (TachyonInternal, snapshot,
    TachyonLOpenCLInternal) and return it as an Image; with path, also write the file as
    `render method path` writes it (format by extension, TGA otherwise). size=(w, h) renders
    at that display size, aasamples/aosamples with those sample counts, for this image only.
    A failure raises TclError with molscope's message."""
    if not isinstance(method, str):
        raise TypeError("render: method must be a string")
    w_h = _size(size) if size is not None else None
    resize = _Setting(lambda: [int(x) for x in split(call("display", "get", "size"))],
                      lambda v: call("display", "resize", v[0], v[1]), w_h)
    aa = _Setting(lambda: int(call("render", "aasamples", method)),
                  lambda v: call("render", "aasamples", method, int(v)), aasamples)
    ao = _Setting(lambda: int(call("render", "aosamples", method)),
                  lambda v: call("render", "aosamples", method, int(v)), aosamples)
    target = None if path is None else os.fspath(path)
    with resize, aa, ao:
        width, height, rgb, png = _molscope.render_image(method, target)
    return Image(width, height, rgb, png)


__all__ = ["render", "Image", "TclError"]
