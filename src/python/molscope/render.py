"""render: VMD's Python `render` module: the render methods and rendering to a file."""
from ._tcl import call_list, call


def listall():
    return call_list("render", "list")


def render(method, filename):
    call("render", method, filename)
