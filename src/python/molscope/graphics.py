"""graphics: VMD's Python `graphics` module: a molecule's user graphics (the graphics
command). Each shape returns its id."""
from ._tcl import call, call_list, vec


def _g(molid, *words):
    return call("graphics", int(molid), *words)


def point(molid, v):
    return int(_g(molid, "point", vec(v)))


def line(molid, v1, v2, style="solid", width=1):
    return int(_g(molid, "line", vec(v1), vec(v2), "style", style, "width", int(width)))


def sphere(molid, center=(0, 0, 0), radius=1.0, resolution=6):
    return int(_g(molid, "sphere", vec(center), "radius", float(radius),
                  "resolution", int(resolution)))


def cylinder(molid, v1, v2, radius=1.0, resolution=6, filled=False):
    return int(_g(molid, "cylinder", vec(v1), vec(v2), "radius", float(radius),
                  "resolution", int(resolution), "filled", "yes" if filled else "no"))


def cone(molid, v1, v2, radius=1.0, radius2=0.0, resolution=6):
    return int(_g(molid, "cone", vec(v1), vec(v2), "radius", float(radius),
                  "radius2", float(radius2), "resolution", int(resolution)))


def triangle(molid, v1, v2, v3):
    return int(_g(molid, "triangle", vec(v1), vec(v2), vec(v3)))


def text(molid, position, text, size=1.0, width=1.0):
    return int(_g(molid, "text", vec(position), text, "size", float(size),
                  "thickness", float(width)))


def color(molid, c):
    return int(_g(molid, "color", c))


def material(molid, name):
    return int(_g(molid, "material", name))


def materials(molid, on):
    return int(_g(molid, "materials", "on" if on else "off"))


def delete(molid, which):
    _g(molid, "delete", which)


def listall(molid):
    return [int(w) for w in call_list("graphics", int(molid), "list")]


def info(molid, gid):
    return _g(molid, "info", int(gid))
