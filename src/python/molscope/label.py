"""label: VMD's Python `label` module: atom, bond, angle and dihedral labels (the label
command). Labels are named by their category and index, as in Tcl."""
from ._tcl import call, call_list, split

ATOM, BOND, ANGLE, DIHEDRAL = "Atoms", "Bonds", "Angles", "Dihedrals"


def listall(category):
    """The labels of a category as Tcl lists them (one entry per label)."""
    return call_list("label", "list", category)


def add(category, molids, atomids):
    """Label atoms (one molid per atom); the new label's index."""
    if len(molids) != len(atomids):
        raise ValueError("label.add: molids and atomids differ in length")
    return int(call("label", "add", category,
                    *("%d/%d" % (int(m), int(a)) for m, a in zip(molids, atomids))))


def show(category, index):
    call("label", "show", category, int(index))


def hide(category, index):
    call("label", "hide", category, int(index))


def delete(category, index):
    call("label", "delete", category, int(index))


def get_values(category, index):
    """The values of a geometry label over the frames (label graph)."""
    return [float(w) for w in split(call("label", "graph", category, int(index)))]


def textsize(size=None):
    """Set the labels' text size unless size is None; the size."""
    if size is not None:
        call("label", "textsize", float(size))
    return float(call("label", "textsize"))


def textthickness(thickness=None):
    if thickness is not None:
        call("label", "textthickness", float(thickness))
    return float(call("label", "textthickness"))
