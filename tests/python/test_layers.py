#!/usr/bin/python3
"""test_layers.py: the layers of src/ (doc/ARCHITECTURE.md) hold. From the sources themselves
it computes which module includes which (a module is a folder of src/; an edge is an
#include "other/file.h") and checks that:
  - every module has a layer in the table below, the same table as doc/ARCHITECTURE.md's;
  - the include graph has no cycle;
  - a module includes only modules of its own layer or of the layers below;
  - the devices see only the devices, the scene, images, cl/ and the foundation (never a
    molecule, a rep, the world or the application);
  - no file below the Tcl bindings reaches <tcl.h>, directly or through any header it
    includes;
  - src/molscope.h, the map, names every module once and includes a header of each.
Prints PASS:/FAIL: lines (and the graph, for the log)."""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mstest import Reporter  # noqa: E402

# The layers, bottom first. A module may include its own layer and the layers below.
LAYERS = [
    ("foundation", ["base", "vecmath"]),
    ("data", ["molecule", "fileio", "image", "cl", "imd"]),
    ("core", ["ss", "select", "measure", "pbc", "surf", "parallel", "movie", "scene"]),
    ("reps", ["rep"]),
    ("devices", ["render", "gl", "rt", "oclrt"]),
    ("assembly", ["assemble"]),
    ("bindings", ["app", "commands", "live", "python"]),
    ("program", ["main"]),
]
TCL_FROM = "bindings"          # the first layer that may use Tcl
DEVICES = "devices"
DEVICES_SEE = {"scene", "image", "base", "vecmath", "cl"}   # besides the devices themselves
TCL_HEADERS = {"tcl.h", "tclInt.h", "tclDecls.h", "tk.h"}

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')

SRCDIR = os.environ.get("MS_SRCDIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__))))
SRC = os.path.join(SRCDIR, "src")


def modules():
    # a folder with sources (an old build may leave a folder of objects behind)
    return sorted(d for d in os.listdir(SRC)
                  if os.path.isdir(os.path.join(SRC, d)) and not d.startswith(".")
                  and any(f.endswith((".c", ".h")) for f in os.listdir(os.path.join(SRC, d))))


def sources(mod):
    d = os.path.join(SRC, mod)
    return sorted(os.path.join(d, f) for f in os.listdir(d) if f.endswith((".c", ".h")))


def includes(path):
    """[(kind, name, line number)] of a file's #include lines (kind '<' or '"')."""
    out = []
    with open(path, errors="replace") as f:
        for i, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                out.append((m.group(1), m.group(2), i))
    return out


def resolve(path, name):
    """The file a quoted include names, or None (system headers, generated files)."""
    for base in (os.path.dirname(path), SRC, os.path.join(SRCDIR, "plugins")):
        cand = os.path.normpath(os.path.join(base, name))
        if os.path.isfile(cand):
            return cand
    return None


def module_of(path):
    rel = os.path.relpath(path, SRC)
    parts = rel.split(os.sep)
    return parts[0] if len(parts) > 1 and not rel.startswith("..") else None


def graph(mods):
    """edges[a] = {b: [file:line that includes b]}."""
    edges = {m: {} for m in mods}
    for m in mods:
        for path in sources(m):
            for kind, name, line in includes(path):
                if kind != '"':
                    continue
                target = resolve(path, name)
                b = module_of(target) if target else None
                if b and b != m and b in edges:
                    edges[m].setdefault(b, []).append(
                        "%s:%d" % (os.path.relpath(path, SRCDIR), line))
    return edges


def cycles(edges):
    """The strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def tcl_chain(path, seen):
    """The include chain from path to a Tcl header, or None."""
    if path in seen:
        return None
    seen.add(path)
    for kind, name, line in includes(path):
        if os.path.basename(name) in TCL_HEADERS:
            return ["%s:%d <%s>" % (os.path.relpath(path, SRCDIR), line, name)]
        if kind == '"':
            target = resolve(path, name)
            if target and target.endswith(".h"):
                rest = tcl_chain(target, seen)
                if rest:
                    return ["%s:%d" % (os.path.relpath(path, SRCDIR), line)] + rest
    return None


def doc_layers():
    """The layer table of doc/ARCHITECTURE.md: [(layer, [modules])]."""
    path = os.path.join(SRCDIR, "doc", "ARCHITECTURE.md")
    rows = []
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not line.startswith("|") or len(cells) < 2:
                continue
            mods = re.findall(r"`([a-z]+)/`", cells[1])
            name = cells[0].strip("* ").lower()
            if mods:
                rows.append((name, mods))
    return rows


def main():
    r = Reporter("layers")
    mods = modules()
    layer_of = {}
    for k, (name, ms) in enumerate(LAYERS):
        for m in ms:
            layer_of[m] = k
    unknown = [m for m in mods if m not in layer_of]
    gone = [m for k in LAYERS for m in k[1] if m not in mods]
    r.report(not unknown and not gone, "every module of src/ has a layer in the table",
             "no layer: %s; not in src/: %s" % (" ".join(unknown), " ".join(gone)))
    edges = graph(mods)
    for m in mods:
        print("# %-9s -> %s" % (m, " ".join(sorted(edges[m]))))

    cyc = cycles(edges)
    r.report(not cyc, "the module include graph has no cycle",
             "; ".join(" <-> ".join(c) for c in cyc))

    bad = []
    for a in mods:
        for b, where in sorted(edges[a].items()):
            if a in layer_of and b in layer_of and layer_of[b] > layer_of[a]:
                bad.append("%s (%s) includes %s (%s) at %s" % (
                    a, LAYERS[layer_of[a]][0], b, LAYERS[layer_of[b]][0], where[0]))
    r.report(not bad, "every module includes only its own layer and those below",
             "; ".join(bad))

    devices = dict(LAYERS)[DEVICES]
    bad = ["%s includes %s at %s" % (a, b, where[0])
           for a in devices if a in edges for b, where in sorted(edges[a].items())
           if b not in devices and b not in DEVICES_SEE]
    r.report(not bad, "the devices see only the scene, images, the foundation and each other",
             "; ".join(bad))

    tcl_layer = [n for n, _ in LAYERS].index(TCL_FROM)
    bad = []
    for m in mods:
        if layer_of.get(m, tcl_layer) >= tcl_layer:
            continue
        for path in sources(m):
            chain = tcl_chain(path, set())
            if chain:
                bad.append(" -> ".join(chain))
    r.report(not bad, "no file below the Tcl bindings reaches <tcl.h>, directly or through "
             "a header", "; ".join(bad[:5]))
    tcl_users = sorted({module_of(p) for m in mods for p in sources(m) if tcl_chain(p, set())})
    print("# Tcl is used in: %s" % " ".join(tcl_users))
    r.report(set(tcl_users) <= {m for m in mods if layer_of.get(m, 0) >= tcl_layer},
             "the modules that use Tcl are all in the bindings or above",
             "Tcl is used in: %s" % " ".join(tcl_users))

    doc = doc_layers()[::-1]    # the page lists the layers top first
    r.report(doc == [(n, ms) for n, ms in LAYERS],
             "doc/ARCHITECTURE.md's layer table is this one",
             "doc: %s" % doc)

    with open(os.path.join(SRC, "molscope.h")) as f:
        text = f.read()
    comment = text[:text.index("*/")]
    listed = re.findall(r"^ \*   ([a-z]+)/ ", comment, re.M)
    twice = sorted({m for m in listed if listed.count(m) > 1})
    r.report(sorted(set(listed)) == mods and not twice,
             "src/molscope.h's map names every module once",
             "missing: %s; not modules: %s; twice: %s" % (
                 " ".join(sorted(set(mods) - set(listed))),
                 " ".join(sorted(set(listed) - set(mods))), " ".join(twice)))
    order = [layer_of.get(m, -1) for m in listed]
    r.report(order == sorted(order), "src/molscope.h's map lists the modules layer by layer",
             " ".join(listed))
    inc = {name.split("/")[0] for kind, name, line in includes(os.path.join(SRC, "molscope.h"))}
    missing = [m for m in mods if any(p.endswith(".h") for p in sources(m)) and m not in inc]
    r.report(not missing, "src/molscope.h includes a header of every module with one",
             " ".join(missing))
    return 1 if r.failures else 0


if __name__ == "__main__":
    sys.exit(main())
