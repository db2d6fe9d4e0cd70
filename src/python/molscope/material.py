"""material: VMD's Python `material` module (the material command)."""
from ._tcl import call, call_list, floats

_KEYS = ("ambient", "specular", "diffuse", "shininess", "mirror", "opacity", "outline",
         "outlinewidth", "transmode")


def listall():
    return call_list("material", "list")


def settings(name):
    """A material's settings, by name (material settings gives them in this order)."""
    return dict(zip(_KEYS, floats(call_list("material", "settings", name))))


def add(name=None, copy=None):
    words = ["material", "add"] + ([name] if name else []) + (["copy", copy] if copy else [])
    return call(*words)


def delete(name):
    call("material", "delete", name)


def rename(oldname, newname):
    call("material", "rename", oldname, newname)


def change(name, **values):
    """Change settings: ambient=, diffuse=, specular=, shininess=, mirror=, opacity=, ..."""
    for key, value in values.items():
        if key not in _KEYS:
            raise ValueError("material.change: unknown setting '%s'" % key)
        call("material", "change", key, name, value)


def default(name):
    call("material", "default", name)
