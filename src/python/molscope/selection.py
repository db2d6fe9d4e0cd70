"""selection: VMD's Python `selection` module: the atom selection macros (`atomselect macro`
and `atomselect delmacro`)."""
from ._tcl import call, call_list


def add_macro(name, selection):
    call("atomselect", "macro", name, selection)


def get_macro(name):
    """The selection text of a macro (TclError when there is none)."""
    return call("atomselect", "macro", name)


def all_macros():
    return call_list("atomselect", "macro")


def del_macro(name):
    call("atomselect", "delmacro", name)
