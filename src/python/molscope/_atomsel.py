"""_atomsel.py: VMD's Python atomsel class, one Tcl atomselect object underneath: the
selection text, molecule and frame; get/set of any keyword; the measurements (center,
rmsd, fit, minmax, sasa, contacts, hbonds, rgyr, rmsf) are molscope's measure commands on
it, and move/moveby its methods. Matrices are 16 numbers in VMD's Python order (column
after column, as OpenGL stores them); Tcl's are rows."""
from ._tcl import TclError, call, call_list, split, floats, ints, molid as _m, vec


def _weight(weight):
    """measure's weight word: a keyword name as is, or a list of numbers."""
    if weight is None:
        return []
    return ["weight", weight if isinstance(weight, str) else vec(weight)]


def _matrix_to_tcl(m):
    m = [float(x) for x in m]
    if len(m) != 16:
        raise ValueError("a matrix is 16 numbers, not %d" % len(m))
    return [[m[c * 4 + r] for c in range(4)] for r in range(4)]


def _matrix_from_tcl(text):
    rows = [floats(split(r)) for r in split(text)]
    return tuple(rows[r][c] for c in range(4) for r in range(4))


def _frame_word(frame):
    return "now" if frame is None or int(frame) < 0 else int(frame)


class atomsel(object):
    """atomsel(selection='all', molid=-1, frame=-1): the atoms of molecule molid (-1: the
    top one) that selection picks, at a frame (-1: the molecule's current one)."""

    def __init__(self, selection="all", molid=-1, frame=-1):
        self._name = None
        self._name = call("atomselect", _m(molid), selection, "frame", _frame_word(frame))
        call(self._name, "global")

    def __del__(self):
        if self._name:
            try:
                call(self._name, "delete")
            except Exception:
                pass    # the application ended first

    # -- what it is
    @property
    def molid(self):
        return int(call(self._name, "molid"))

    @property
    def text(self):
        return call(self._name, "text")

    @property
    def frame(self):
        """The frame it reads (-1: the molecule's current one, whichever it is)."""
        f = call(self._name, "frame")
        return -1 if f == "now" else int(f)

    @frame.setter
    def frame(self, value):
        call(self._name, "frame", _frame_word(value))

    def __str__(self):
        return self.text

    def __repr__(self):
        return "atomsel('%s', molid=%d, frame=%d)" % (self.text, self.molid, self.frame)

    def __len__(self):
        return int(call(self._name, "num"))

    def __iter__(self):
        return iter(ints(call_list(self._name, "list")))

    def __contains__(self, index):
        return int(index) in set(self)

    def update(self):
        """Select again (after the frame's coordinates or the atoms changed)."""
        call(self._name, "update")

    # -- attributes
    def get(self, attrib):
        """The values of one keyword for every selected atom, as numbers where they are."""
        return [_number(w) for w in call_list(self._name, "get", attrib)]

    def set(self, attrib, value):
        """Set a keyword: one value for every atom, or a sequence of one per atom."""
        if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
            value = [value] * len(self)
        call(self._name, "set", attrib, list(value))

    @property
    def bonds(self):
        return [ints(split(b)) for b in call_list(self._name, "getbonds")]

    @bonds.setter
    def bonds(self, lists):
        call(self._name, "setbonds", [[int(i) for i in b] for b in lists])

    def write(self, filetype, filename):
        call(self._name, "write" + filetype, filename)

    # -- moving
    def moveby(self, vector):
        call(self._name, "moveby", vec(vector))

    def move(self, matrix):
        call(self._name, "move", _matrix_to_tcl(matrix))

    # -- measuring
    def center(self, weight=None):
        return tuple(floats(call_list("measure", "center", self._name, *_weight(weight))))

    def rmsd(self, selection, weight=None):
        return float(call("measure", "rmsd", self._name, selection._name, *_weight(weight)))

    def fit(self, selection, weight=None):
        """The matrix moving these atoms onto selection's (16 numbers)."""
        return _matrix_from_tcl(call("measure", "fit", self._name, selection._name,
                                     *_weight(weight)))

    def rgyr(self, weight=None):
        return float(call("measure", "rgyr", self._name, *_weight(weight)))

    def rmsf(self, first=0, last=-1, step=1):
        return floats(call_list("measure", "rmsf", self._name, "first", int(first),
                                "last", int(last), "step", int(step)))

    def minmax(self, radii=False):
        lo, hi = call_list("measure", "minmax", self._name, *(["-withradii"] if radii else []))
        return tuple(floats(split(lo))), tuple(floats(split(hi)))

    def sasa(self, srad, samples=-1, points=False, restrict=None):
        """The solvent-accessible surface area (and, with points, the surface points)."""
        words = ["measure", "sasa", float(srad), self._name]
        if int(samples) > 0:
            words += ["-samples", int(samples)]
        if restrict is not None:
            words += ["-restrict", restrict._name]
        if points:
            words += ["-points", "::_molscope_sasa_points"]
        area = float(call(*words))
        if not points:
            return area
        pts = [tuple(floats(split(p))) for p in call_list("set", "::_molscope_sasa_points")]
        call("unset", "::_molscope_sasa_points")
        return area, pts

    def contacts(self, selection, cutoff):
        """Pairs of atoms closer than cutoff: [indices here, indices in selection]."""
        return [ints(split(w)) for w in call_list("measure", "contacts", float(cutoff),
                                                   self._name, selection._name)]

    def hbonds(self, cutoff, maxangle, acceptor=None):
        """Hydrogen bonds: [donors, acceptors, hydrogens] (atom indices)."""
        words = ["measure", "hbonds", float(cutoff), float(maxangle), self._name]
        if acceptor is not None:
            words.append(acceptor._name)
        return [ints(split(w)) for w in call_list(*words)]


def _number(word):
    """A Tcl value as VMD's Python gives it: int, float, or the string."""
    try:
        return int(word)
    except ValueError:
        pass
    try:
        return float(word)
    except ValueError:
        return word


atomsel.atomsel = atomsel    # `from atomsel import atomsel` (VMD 1.9.3's module name)
__all__ = ["atomsel", "TclError"]
