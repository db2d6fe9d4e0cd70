"""color: VMD's Python `color` module: colour categories and their items, the colour
table and the colour scale (the color and colorinfo commands)."""
from ._tcl import call, call_list, floats


def categories():
    return call_list("colorinfo", "categories")


def get_colormap(name):
    """A category as a dict: item -> colour name."""
    return {item: call("colorinfo", "category", name, item)
            for item in call_list("colorinfo", "category", name)}


def set_colormap(name, pairs):
    for item, color in pairs.items():
        call("color", name, item, color)


def get_colors():
    """Every named colour: name -> (r, g, b)."""
    return {c: tuple(floats(call_list("colorinfo", "rgb", c)))
            for c in call_list("colorinfo", "colors")}


def get_colorlist():
    """The (r, g, b) of every colour id, the named ones then the scale."""
    n = int(call("colorinfo", "max"))
    return [tuple(floats(call_list("colorinfo", "rgb", i))) for i in range(n)]


def set_colors(colors):
    for name, rgb in colors.items():
        set_colorid(name, rgb)


def set_colorid(name, rgb):
    call("color", "change", "rgb", name, *(float(x) for x in rgb))


def scale_method():
    return call("colorinfo", "scale", "method")


def scale_methods():
    return call_list("colorinfo", "scale", "methods")


def scale_midpoint():
    return float(call("colorinfo", "scale", "midpoint"))


def scale_min():
    return float(call("colorinfo", "scale", "min"))


def scale_max():
    return float(call("colorinfo", "scale", "max"))


def set_scale(method=None, midpoint=None, min=None, max=None):
    for key, value in (("method", method), ("midpoint", midpoint), ("min", min),
                       ("max", max)):
        if value is not None:
            call("color", "scale", key, value)
