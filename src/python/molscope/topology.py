"""topology: VMD's Python `topology` module: a molecule's bonds, angles, dihedrals and
impropers with their types, listed, added and deleted. Each function is one command of
molscope's topotools (`topo -molid <m> ...`, tcl/topotools), whose C half keeps the terms."""
from ._tcl import call, call_list, split, molid as _molid

_KINDS = {"angle": 3, "dihedral": 4, "improper": 4}


def _topo(molid, *words, listed=True):
    """`topo -molid <m> words...`: its result as a list (listed) or a string."""
    call("package", "require", "topotools")
    return (call_list if listed else call)("topo", "-molid", _molid(molid), *words)


def bonds(molid=-1, type=False, order=False):
    """The bonds as (i, j), with type and/or order appended when asked: (i, j, type, order)."""
    flag = "both" if type and order else "type" if type else "order" if order else "none"
    out = []
    for b in _topo(molid, "getbondlist", flag):
        w = split(b)
        t = [int(w[0]), int(w[1])]
        if type:
            t.append(w[2])
        if order:
            t.append(float(w[-1]))
        out.append(tuple(t))
    return out


def _terms(kind, molid, type):
    """getanglelist / getdihedrallist / getimproperlist ({type i j k ...} each) as VMD's
    tuples: the atoms, then the type when asked."""
    out = []
    for term in _topo(molid, "get%slist" % kind):
        w = split(term)
        atoms = tuple(int(x) for x in w[1:1 + _KINDS[kind]])
        out.append(atoms + ((w[0],) if type else ()))
    return out


def angles(molid=-1, type=False):
    return _terms("angle", molid, type)


def dihedrals(molid=-1, type=False):
    return _terms("dihedral", molid, type)


def impropers(molid=-1, type=False):
    return _terms("improper", molid, type)


def addbond(i, j, molid=-1, order=1.0, type=None):
    """Add a bond (order 1 and no type unless given)."""
    words = ["addbond", int(i), int(j), "-bondorder", float(order)]
    if type is not None:
        words += ["-bondtype", type]
    _topo(molid, *words)


def _addterm(kind, atoms, molid, type):
    words = ["add" + kind] + [int(a) for a in atoms]
    _topo(molid, *(words + ([] if type is None else [type])))


def addangle(i, j, k, molid=-1, type=None):
    _addterm("angle", (i, j, k), molid, type)


def adddihedral(i, j, k, l, molid=-1, type=None):
    _addterm("dihedral", (i, j, k, l), molid, type)


def addimproper(i, j, k, l, molid=-1, type=None):
    _addterm("improper", (i, j, k, l), molid, type)


def delbond(i, j, molid=-1):
    _topo(molid, "delbond", int(i), int(j))


def delangle(i, j, k, molid=-1):
    _topo(molid, "delangle", int(i), int(j), int(k))


def deldihedral(i, j, k, l, molid=-1):
    _topo(molid, "deldihedral", int(i), int(j), int(k), int(l))


def delimproper(i, j, k, l, molid=-1):
    _topo(molid, "delimproper", int(i), int(j), int(k), int(l))


def _del_all(kind, molid):
    """Clear every term of a kind; how many there were."""
    n = int(_topo(molid, "num%ss" % kind, listed=False))
    _topo(molid, "clear%ss" % kind)
    return n


def del_all_bonds(molid=-1):
    return _del_all("bond", molid)


def del_all_angles(molid=-1):
    return _del_all("angle", molid)


def del_all_dihedrals(molid=-1):
    return _del_all("dihedral", molid)


def del_all_impropers(molid=-1):
    return _del_all("improper", molid)


def bondtypes(molid=-1):
    return _topo(molid, "bondtypenames")


def angletypes(molid=-1):
    return _topo(molid, "angletypenames")


def dihedraltypes(molid=-1):
    return _topo(molid, "dihedraltypenames")


def impropertypes(molid=-1):
    return _topo(molid, "impropertypenames")
