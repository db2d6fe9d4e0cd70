"""molrep: VMD's Python `molrep` module: a molecule's representations (style, colouring,
selection, material, visibility), each function molscope's mol/molinfo rep commands."""
from ._tcl import call, call_list, boolean


def _get(molid, key, rep):
    return call_list("molinfo", int(molid), "get", ["%s %d" % (key, int(rep))])[0]


def num(molid):
    return int(call_list("molinfo", int(molid), "get", "numreps")[0])


def addrep(molid, style=None, color=None, selection=None, material=None):
    """A new rep made from the current defaults, then changed as given. Its index."""
    call("mol", "addrep", int(molid))
    rep = num(molid) - 1
    try:
        modrep(molid, rep, style=style, sel=selection, color=color, material=material)
    except Exception:
        call("mol", "delrep", rep, int(molid))
        raise
    return rep


def delrep(molid, rep):
    call("mol", "delrep", int(rep), int(molid))


def modrep(molid, rep, style=None, sel=None, color=None, material=None):
    for sub, value in (("modstyle", style), ("modselect", sel), ("modcolor", color),
                       ("modmaterial", material)):
        if value is not None:
            call("mol", sub, int(rep), int(molid), *str(value).split())


def get_style(molid, rep):
    return _get(molid, "rep", rep)


def get_selection(molid, rep):
    return _get(molid, "selection", rep)


def get_color(molid, rep):
    return _get(molid, "color", rep)


def get_material(molid, rep):
    return _get(molid, "material", rep)


def get_repname(molid, rep):
    return call("mol", "repname", int(molid), int(rep))


def repindex(molid, name):
    return int(call("mol", "repindex", int(molid), name))


def get_visible(molid, rep):
    return boolean(call("mol", "showrep", int(molid), int(rep)))


def set_visible(molid, rep, visible):
    call("mol", "showrep", int(molid), int(rep), "on" if visible else "off")
