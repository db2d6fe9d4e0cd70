"""display: VMD's Python `display` module: the display's settings (`display get` and the
`display` subcommands that set them) and screen updates."""
from ._tcl import call, split

_SETTINGS = ("eyesep", "focallength", "height", "distance", "nearclip", "farclip",
             "antialias", "depthcue", "culling", "stereo", "projection", "size")
PROJ_PERSP = "Perspective"
PROJ_ORTHO = "Orthographic"


def update():
    call("display", "update")


def update_ui():
    call("display", "update", "ui")


def update_on():
    call("display", "update", "on")


def update_off():
    call("display", "update", "off")


def get(key):
    """One setting, as a number, a [width, height] size, or a word."""
    if key not in _SETTINGS:
        raise ValueError("display.get: unknown setting '%s': must be %s" % (key, ", ".join(_SETTINGS)))
    v = call("display", "get", key)
    if key == "size":
        return [int(w) for w in split(v)]
    try:
        return float(v)
    except ValueError:
        return v


def set(**settings):
    """Change settings by name (eyesep=, nearclip=, projection=, size=[w, h], ...)."""
    for key, value in settings.items():
        if key not in _SETTINGS:
            raise ValueError("display.set: unknown setting '%s'" % key)
        if key == "size":
            call("display", "resize", int(value[0]), int(value[1]))
        elif key in ("nearclip", "farclip"):
            call("display", key, "set", value)
        elif key in ("antialias", "depthcue", "culling"):
            call("display", key, "on" if value else "off")
        else:
            call("display", key, value)


def stereomodes():
    return split(call("display", "stereomodes"))
