"""axes: VMD's Python `axes` module: where the axes are drawn (`axes location`)."""
from ._tcl import call

OFF = "Off"
ORIGIN = "Origin"
LOWERLEFT = "LowerLeft"
LOWERRIGHT = "LowerRight"
UPPERLEFT = "UpperLeft"
UPPERRIGHT = "UpperRight"


def get_location():
    return call("axes", "location")


def set_location(location):
    call("axes", "location", location)


def get_locations():
    """The locations `axes location` accepts."""
    return [OFF, ORIGIN, LOWERLEFT, LOWERRIGHT, UPPERLEFT, UPPERRIGHT]
