"""measure: VMD's Python `measure` module (VMD 1.9.4: bond, angle, dihedral, imprp, by atom
index, one value per frame) and the selection measures of the Tcl `measure` command taking
atomsel objects (center, rmsd, fit, minmax, rgyr, rmsf, sasa, contacts, hbonds). Each is the
Tcl `measure` subcommand of the same name; the selection measures are the atomsel methods
that run it."""
from ._tcl import call_list, floats, molid as _molid


def _frames(frame, first, last):
    """The frame words of `measure bond|angle|dihed|imprp`: a frame, a range, or none (the
    default molecule's current frame)."""
    if first != -1 or last != -1:
        words = []
        if first != -1:
            words += ["first", int(first)]
        if last != -1:
            words += ["last", int(last)]
        return words
    return [] if frame == -1 else ["frame", int(frame)]


def _geom(sub, atoms, molids, frame, first, last):
    """`measure <sub> {{i m} ...} molid m frame f` (or first/last): one value per frame."""
    m0 = _molid(molids[0])
    pairs = [[int(a), m0 if m is None or m == -1 else _molid(m)]
             for a, m in zip(atoms, molids)]
    return floats(call_list("measure", sub, pairs, "molid", m0,
                            *_frames(frame, first, last)))


def bond(atom1, atom2, molid=-1, molid2=-1, frame=-1, first=-1, last=-1):
    """The distance between two atoms (molid2 -1: molid's), per frame."""
    return _geom("bond", (atom1, atom2), (molid, molid2), frame, first, last)


def angle(atom1, atom2, atom3, molid=-1, molid2=-1, molid3=-1, frame=-1, first=-1, last=-1):
    """The angle at atom2 in degrees, per frame."""
    return _geom("angle", (atom1, atom2, atom3), (molid, molid2, molid3), frame, first, last)


def dihedral(atom1, atom2, atom3, atom4, molid=-1, molid2=-1, molid3=-1, molid4=-1,
             frame=-1, first=-1, last=-1):
    """The dihedral angle in degrees (-180 to 180), per frame."""
    return _geom("dihed", (atom1, atom2, atom3, atom4), (molid, molid2, molid3, molid4),
                 frame, first, last)


def imprp(atom1, atom2, atom3, atom4, molid=-1, molid2=-1, molid3=-1, molid4=-1,
          frame=-1, first=-1, last=-1):
    """The improper dihedral angle in degrees, per frame."""
    return _geom("imprp", (atom1, atom2, atom3, atom4), (molid, molid2, molid3, molid4),
                 frame, first, last)


def center(sel, weight=None):
    return sel.center(weight)


def rmsd(sel1, sel2, weight=None):
    return sel1.rmsd(sel2, weight)


def fit(sel1, sel2, weight=None):
    """The matrix moving sel1 onto sel2 (16 numbers, as atomsel.fit)."""
    return sel1.fit(sel2, weight)


def minmax(sel, radii=False):
    return sel.minmax(radii)


def rgyr(sel, weight=None):
    return sel.rgyr(weight)


def rmsf(sel, first=0, last=-1, step=1):
    return sel.rmsf(first, last, step)


def sasa(srad, sel, samples=-1, points=False, restrict=None):
    """`measure sasa srad sel`: the area (and the points with points=True)."""
    return sel.sasa(srad, samples, points, restrict)


def contacts(cutoff, sel1, sel2=None):
    """`measure contacts cutoff sel1 ?sel2?`: [indices in sel1, indices in sel2]."""
    return sel1.contacts(sel1 if sel2 is None else sel2, cutoff)


def hbonds(cutoff, maxangle, donor, acceptor=None):
    """`measure hbonds cutoff angle donor ?acceptor?`: [donors, acceptors, hydrogens]."""
    return donor.hbonds(cutoff, maxangle, acceptor)
