"""trans: VMD's Python `trans` module: turning, moving and scaling the view, and each
molecule's centre, matrices, fixed and shown flags (rotate/translate/scale and molinfo)."""
from ._tcl import call, call_list, split, floats, boolean, vec


def rotate(axis, angle):
    call("rotate", axis, "by", float(angle))


def translate(x, y, z):
    call("translate", "by", float(x), float(y), float(z))


def scale(factor):
    call("scale", "by", float(factor))


def resetview(molid=None):
    """VMD's resetview (molid is accepted for VMD's signature: the view of every molecule
    is reset, as `display resetview` does)."""
    call("display", "resetview")


def _get(molid, key):
    return call_list("molinfo", int(molid), "get", key)[0]


def get_center(molid):
    return tuple(floats(split(_get(molid, "center"))))


def set_center(molid, center):
    call("molinfo", int(molid), "set", "center", [vec(center)])


def _matrix(molid, key):
    return [floats(split(r)) for r in split(_get(molid, key))]


def get_rotation(molid):
    """The molecule's rotation matrix: 4 rows of 4."""
    return _matrix(molid, "rotate_matrix")


def get_scale(molid):
    return _matrix(molid, "scale_matrix")[0][0]


def is_fixed(molid):
    return boolean(_get(molid, "fixed"))


def fix(molid, fixed):
    call("mol", "fix" if fixed else "free", int(molid))


def is_shown(molid):
    return boolean(_get(molid, "drawn"))


def show(molid, shown):
    call("mol", "on" if shown else "off", int(molid))
