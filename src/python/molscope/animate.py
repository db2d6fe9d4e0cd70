"""animate: VMD's Python `animate` module: playing the frames of the active molecules and
which molecules are active (the animate command and mol active/inactive)."""
from ._tcl import call, call_list, boolean


def once():
    call("animate", "style", "once")


def rock():
    call("animate", "style", "rock")


def loop():
    call("animate", "style", "loop")


def style():
    return call("animate", "style")


def goto(frame):
    call("animate", "goto", int(frame))


def reverse():
    call("animate", "reverse")


def forward():
    call("animate", "forward")


def prev():
    call("animate", "prev")


def next():
    call("animate", "next")


def pause():
    call("animate", "pause")


def speed(value=-1):
    """Set the speed (0..1) unless value is negative; the speed."""
    return float(call("animate", "speed", value) if value >= 0 else call("animate", "speed"))


def skip(value=-1):
    return int(call("animate", "skip", int(value)) if value >= 1 else call("animate", "skip"))


def is_active(molid):
    return boolean(call_list("molinfo", int(molid), "get", "active")[0])


def activate(molid, active):
    call("mol", "active" if active else "inactive", int(molid))
