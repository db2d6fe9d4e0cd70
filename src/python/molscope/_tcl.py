"""_tcl.py: the few helpers every module of the molscope package uses to run molscope's
Tcl commands through _molscope (the words go over as a list, never re-quoted; a Python
list or tuple becomes a Tcl list) and to read their results as Python values. No module of the package computes what a Tcl command
computes: each function is one command, or a few, and their results."""
import _molscope

TclError = _molscope.TclError
call = _molscope.call
call_list = _molscope.call_list
split = _molscope.split


def floats(words):
    """A list of numbers as printed by Tcl, as floats."""
    return [float(w) for w in words]


def ints(words):
    return [int(w) for w in words]


def molid(m):
    """A molecule id as Tcl reads it; -1 (VMD's Python) or None mean the top molecule."""
    if m is None or (isinstance(m, int) and m < 0):
        return "top"
    return int(m)


def top():
    """The top molecule's id (-1 when there is none)."""
    return int(call("molinfo", "top"))


def vec(v):
    """A sequence of numbers as one Tcl list word (call makes a list a Tcl list)."""
    return [float(x) for x in v]


def onoff(flag):
    return "on" if flag else "off"


def boolean(word):
    """A Tcl boolean word (on/off, 1/0, yes/no, true/false) as a bool."""
    w = word.strip().lower()
    if w in ("1", "on", "yes", "true"):
        return True
    if w in ("0", "off", "no", "false"):
        return False
    raise TclError("expected a boolean but got \"%s\"" % word)
