"""vmdnumpy: VMD's Python `vmdnumpy` module: a frame's coordinates as a numpy array that
is molscope's own float32 memory (no copy, writable: `arr += shift` moves the atoms).
After writing, call molecule.set_frame(molid, molecule.get_frame(molid)) (or any command
that moves atoms) for the representations to redraw. An array outliving its molecule or
frame keeps its data but moves nothing any more (no crash); asking for a deleted molecule
raises ValueError."""
import numpy as _np

import _molscope

from ._atomsel import atomsel as _atomsel
from ._tcl import call_list, molid as _m


def timestep(molid, frame=-1):
    """The x y z of every atom of a frame (-1: the current one): an (natoms, 3) float32
    array sharing memory with the molecule."""
    return _np.asarray(_molscope.frame_buffer(int(molid), int(frame)))


def positions(molid=-1, frame=-1):
    """timestep's array; molid -1 is the top molecule."""
    return timestep(molid, frame)


def atomselect(molid, frame, selection):
    """A 0/1 int array over the molecule's atoms: 1 where selection picks the atom."""
    n = int(call_list("molinfo", _m(molid), "get", "numatoms")[0])
    flags = _np.zeros(n, dtype=_np.int32)
    idx = list(_atomsel(selection, molid, frame))
    flags[idx] = 1
    return flags
