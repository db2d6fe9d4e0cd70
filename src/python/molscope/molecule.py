"""molecule: VMD's Python `molecule` module (load, new, read, write, list, frames, names
and files of molecules), each function one of molscope's mol/molinfo/animate commands.
Invalid molecule ids raise TclError (a ValueError) with the command's message."""
from ._tcl import call, call_list, split, molid as _m, onoff, boolean


def _info(molid, key):
    """One keyword of molinfo: its value (a string)."""
    return call_list("molinfo", _m(molid), "get", key)[0]


def listall():
    """The ids of every molecule, in creation order."""
    return [int(w) for w in call_list("molinfo", "list")]


def num():
    return int(call("molinfo", "num"))


def exists(molid):
    """Whether a molecule with this id exists (1 or 0, as VMD answers)."""
    return int(int(molid) in listall())


def load(struct_type, struct_file, coord_type=None, coord_file=None):
    """A new molecule from struct_file (read as struct_type) and, if given, the frames of
    coord_file; every frame is read before it returns. Its id."""
    if (coord_type is None) != (coord_file is None):
        raise ValueError("molecule.load: coord_type and coord_file go together")
    m = int(call("mol", "new", struct_file, "type", struct_type, "waitfor", "all"))
    if coord_file is not None:
        try:
            call("mol", "addfile", coord_file, "type", coord_type, "waitfor", "all", m)
        except Exception:
            call("mol", "delete", m)    # no half-made molecule is left behind
            raise
    return m


def new(name, natoms=0):
    """A new empty molecule named name, with natoms atoms (and no frames). Its id."""
    natoms = int(natoms)
    if natoms < 0:
        raise ValueError("molecule.new: natoms must be 0 or more, not %d" % natoms)
    m = int(call("mol", "new", "atoms", natoms) if natoms else call("mol", "new"))
    call("mol", "rename", m, name)
    return m


def read(molid, filetype, filename, beg=0, end=-1, skip=1, waitfor=-1, volsets=None):
    """Read the frames beg..end (every skip-th) of filename into molecule molid; every
    frame is read before it returns (waitfor is accepted for VMD's signature). The number
    of frames added."""
    before = numframes(molid)
    words = ["mol", "addfile", filename, "type", filetype, "first", int(beg), "last",
             int(end), "step", int(skip), "waitfor", "all"]
    if volsets is not None:
        for v in volsets:
            words += ["volsets", int(v)]
    call(*(words + [_m(molid)]))
    return numframes(molid) - before


def write(molid, filetype, filename, beg=0, end=-1, stride=1, waitfor=-1, selection=None):
    """Write frames beg..end (every stride-th) of the molecule to filename as filetype;
    selection, an atomsel, limits the atoms. The number of frames written."""
    words = ["animate", "write", filetype, filename, "beg", int(beg),
             "end", -1 if end is None else int(end), "skip", int(stride), "waitfor", "all"]
    if selection is not None:
        words += ["sel", selection._name]
    return int(call(*(words + [_m(molid)])))


def delete(molid):
    call("mol", "delete", int(molid))


def cancel(molid):
    call("mol", "cancel", int(molid))


def rename(molid, name):
    call("mol", "rename", int(molid), name)


def name(molid):
    return _info(molid, "name")


def numatoms(molid):
    return int(_info(molid, "numatoms"))


def numframes(molid):
    return int(_info(molid, "numframes"))


def get_frame(molid):
    return int(_info(molid, "frame"))


def set_frame(molid, frame):
    call("molinfo", _m(molid), "set", "frame", int(frame))


def delframe(molid, beg=0, end=-1, stride=1):
    """Delete frames beg..end, every stride-th, of the molecule."""
    call("animate", "delete", "beg", int(beg), "end", int(end), "skip", max(1, int(stride)),
         _m(molid))


def dupframe(molid, frame=-1):
    """Append a copy of a frame (-1: the current one) to the molecule."""
    call("animate", "dup", "frame", "now" if int(frame) < 0 else int(frame), _m(molid))


def get_filenames(molid):
    return split(_info(molid, "filename"))


def get_filetypes(molid):
    return split(_info(molid, "filetype"))


def get_top():
    return int(call("molinfo", "top"))


def set_top(molid):
    call("mol", "top", int(molid))


def get_visible(molid):
    return boolean(_info(molid, "drawn"))


def set_visible(molid, visible):
    call("mol", onoff(visible), int(molid))


def get_periodic(molid, frame=-1):
    """The unit cell of a frame: a dict of a, b, c, alpha, beta, gamma."""
    keys = ["a", "b", "c", "alpha", "beta", "gamma"]
    fr = "now" if int(frame) < 0 else int(frame)
    vals = call_list("molinfo", _m(molid), "get", " ".join(keys), "frame", fr)
    return dict(zip(keys, (float(v) for v in vals)))


def ssrecalc(molid):
    call("mol", "ssrecalc", int(molid))
