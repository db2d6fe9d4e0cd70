"""_vmdnames.py: VMD's names inside molscope's embedded interpreter: `vmd` is the molscope
package (`import vmd`, `from vmd import molecule, atomsel`), its modules are also
importable under their own names as VMD 1.9.3 scripts import them (`import molecule`,
`from atomsel import atomsel`), and __main__ gets VMD's top-level names."""
import sys

import molscope

_MODULES = ["molecule", "molrep", "display", "render", "trans", "animate", "color", "vmdnumpy",
            "material", "graphics", "label", "measure", "topology", "selection", "axes"]


def install(main_globals):
    sys.modules.setdefault("vmd", molscope)
    for name in _MODULES + ["atomsel"]:
        obj = getattr(molscope, name, None)
        if obj is None:     # vmdnumpy without numpy
            continue
        sys.modules.setdefault("vmd." + name, obj)
        sys.modules.setdefault(name, obj)
        main_globals.setdefault(name, obj)
    main_globals.setdefault("evaltcl", molscope.evaltcl)
    main_globals.setdefault("vmd", molscope)
