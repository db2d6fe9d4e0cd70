"""conftest.py: what the tests of molscope's Python API share: the molscope package (from
the build tree, PYTHONPATH set by tests/python/test_pyapi.py), the test data, a clean
session for every test, and `tcl`, which runs the Tcl command a function wraps so the two
can be compared."""
import os

import pytest

import molscope

SRCDIR = os.environ.get("MS_SRCDIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__))))
DATA = os.environ.get("MS_TEST_DATA") or os.path.join(SRCDIR, "tests", "data")


def data(name):
    return os.path.join(DATA, name)


def tcl(script):
    """A Tcl script's result, as a Tcl user would get it."""
    return molscope.evaltcl(script)


def tcl_list(script):
    return molscope._tcl.split(tcl(script))


def tcl_error(script):
    """The message of a Tcl command that must fail."""
    return tcl("if {[catch {%s} msg]} {set msg} else {error \"no error from: %s\"}"
               % (script, script.replace('"', '\\"')))


@pytest.fixture(autouse=True)
def clean_session():
    tcl("mol delete all")
    yield
    tcl("mol delete all")


@pytest.fixture
def helix():
    """helix.psf with its 10-frame helix.dcd: the molecule's id."""
    return molscope.molecule.load("psf", data("helix.psf"), "dcd", data("helix.dcd"))
