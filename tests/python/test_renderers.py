"""test_renderers.py: the file renderers (Raster3D, RenderMan, STL, VRML-2, X3D) and SGI .rgb
images, read by programs and parsers that are not molscope's: one scene of known primitives
(2 spheres, 1 cylinder, 1 cone, 1 triangle, 1 line) and one of coordination polyhedra is
rendered by molscope; each file is parsed here (XML for X3D, a token reader for VRML, RIB
and r3d, facets for STL) and its geometry counted against the scene, its colours looked for;
Raster3D's own `render` draws the .r3d where it is installed, and its picture is compared
with molscope's snapshot; every image renderer's .rgb is read by ImageMagick and compared
pixel for pixel with the PNG of the same render."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(__file__))
from mstest import Reporter  # noqa: E402

R = Reporter("renderers")
EXE = os.environ.get("MOLSCOPE", "src/molscope")
DATA = os.environ.get("MS_TEST_DATA", "tests/data")
OUT = tempfile.mkdtemp(prefix="renderers-", dir=os.environ.get("MS_TEST_OUT"))

SCENE = """
display resize 160 120
axes location off
color Display Background white
set g [mol new]
graphics $g material Opaque
graphics $g color red
graphics $g sphere {0.6 0.3 0} radius 0.25 resolution 8
graphics $g color blue
graphics $g sphere {-0.6 0.3 -0.5} radius 0.2 resolution 6
graphics $g color green
graphics $g cylinder {-1 -1 0} {0 -0.2 0} radius 0.1 resolution 10 filled yes
graphics $g color orange
graphics $g cone {-1 0.5 0} {-0.5 0.8 0} radius 0.2 resolution 12
graphics $g color yellow
graphics $g triangle {0 -1 0} {1 -1 0} {1 -0.5 0}
graphics $g color black
graphics $g line {-1.5 -1.2 0} {1.5 -1.2 0}
"""
POLY = """
display resize 160 120
axes location off
mol new %s/polyhedra.pdb
mol delrep 0 top
mol representation Polyhedra 3.5
mol selection {name TI SI CS}
mol color ColorID 1
mol addrep top
""" % DATA
FORMATS = [("Raster3D", "r3d"), ("RenderMan", "rib"), ("STL", "stl"), ("VRML-2", "wrl"),
           ("X3D", "x3d"), ("Wavefront", "obj")]


def run(script):
    p = subprocess.run([EXE, "-dispdev", "text"], input=script + "\nquit\n",
                       capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout + p.stderr


def export(scene, stem):
    lines = [scene] + ["render %s %s/%s.%s" % (m, OUT, stem, e) for m, e in FORMATS]
    rc, out = run("\n".join(lines))
    R.report(rc == 0, "%s: every file renderer writes its file" % stem, out[-400:])
    return {e: open("%s/%s.%s" % (OUT, stem, e)).read() for _, e in FORMATS
            if os.path.exists("%s/%s.%s" % (OUT, stem, e))}


def obj_triangles(text):
    """Faces of the Wavefront export: the scene's triangles counted by another exporter."""
    return sum(1 for l in text.splitlines() if l.startswith("f "))


def stl_facets(text):
    """(vertices, normal) of every facet; None when the file is not ASCII STL."""
    if not text.startswith("solid ") or not text.rstrip().endswith("endsolid molscope"):
        return None
    facets = []
    for block in re.findall(r"facet normal (.*?)\n\s*outer loop\n(.*?)endloop", text, re.S):
        n = [float(x) for x in block[0].split()]
        v = [[float(x) for x in l.split()[1:]] for l in block[1].strip().splitlines()]
        if len(v) != 3 or any(not l.strip().startswith("vertex") for l in
                              block[1].strip().splitlines()):
            return None
        facets.append((v, n))
    return facets if len(facets) == text.count("endfacet") else None


def vrml_tokens(text):
    body = "\n".join(l for l in text.splitlines() if not l.startswith("#"))
    return re.findall(r"[{}\[\]]|[^\s{}\[\],]+", body)


def balanced(tokens, pairs):
    stack = []
    for t in tokens:
        if t in pairs:
            stack.append(pairs[t])
        elif t in pairs.values():
            if not stack or stack.pop() != t:
                return False
    return not stack


def check_scene(f):
    ntri = obj_triangles(f["obj"])
    facets = stl_facets(f["stl"])
    R.report(facets is not None and len(facets) == ntri,
             "STL: ASCII facets, as many as the scene's triangles (%d)" % ntri,
             "got %s" % (None if facets is None else len(facets)))
    # VRML-2: one node per solid, the triangle in an IndexedFaceSet, the line in a line set
    t = vrml_tokens(f["wrl"])
    counts = {k: t.count(k) for k in ("Sphere", "Cylinder", "Cone", "IndexedFaceSet",
                                      "IndexedLineSet")}
    R.report(f["wrl"].startswith("#VRML V2.0 utf8") and balanced(t, {"{": "}", "[": "]"}) and
             counts == {"Sphere": 2, "Cylinder": 1, "Cone": 1, "IndexedFaceSet": 1,
                        "IndexedLineSet": 1},
             "VRML-2: header, balanced nodes, 2 spheres, 1 cylinder, 1 cone, 1 face set, 1 "
             "line set", str(counts))
    R.report("color [ 1.000 1.000 0.000" in f["wrl"] and "diffuseColor 0.65 0 0" in f["wrl"],
             "VRML-2: the triangle's yellow and the red sphere's colour are there")
    try:
        root = ET.fromstring(f["x3d"])
        tags = [e.tag for e in root.iter()]
        xc = {k: tags.count(k) for k in ("Sphere", "Cylinder", "Cone", "IndexedFaceSet",
                                         "IndexedLineSet")}
        ok = root.tag == "X3D" and xc == counts
        ifs = root.find(".//IndexedFaceSet")
        ok = ok and ifs.get("coordIndex").split() == ["0", "1", "2", "-1"]
        col = [m.get("diffuseColor") for m in root.iter("Material")]
        R.report(ok and "0 0 0.65" in col, "X3D: well formed, the same nodes, colours", str(xc))
    except ET.ParseError as e:
        R.report(False, "X3D: well formed", str(e))
    check_rib(f["rib"])
    check_r3d(f["r3d"], ntri)


def check_rib(text):
    t = re.findall(r'"[^"]*"|\[|\]|[^\s\[\]"]+', text)
    c = {k: t.count(k) for k in ("Sphere", "Cylinder", "Hyperboloid", "Polygon", "Curves")}
    ok = text.startswith("##RenderMan RIB") and balanced(t, {"[": "]"})
    ok = ok and t.count("WorldBegin") == 1 and t.count("WorldEnd") == 1
    ok = ok and t.count("AttributeBegin") == t.count("AttributeEnd")
    ok = ok and t.count("TransformBegin") == t.count("TransformEnd")
    R.report(ok and c == {"Sphere": 2, "Cylinder": 1, "Hyperboloid": 1, "Polygon": 1,
                          "Curves": 1},
             "RenderMan: balanced blocks, 2 spheres, 1 cylinder, 1 cone, 1 polygon, 1 curve",
             str(c))
    R.report("Color [1.000 0.000 0.000]" in text and 'Format 160 120 1' in text,
             "RenderMan: colours and the display's size")


def r3d_objects(text):
    """The header's numbers and the objects (type, values) of a Raster3D file."""
    lines = text.splitlines()
    head, body = lines[:20], lines[20:]
    objs, i = [], 0
    sizes = {1: 12, 2: 7, 3: 11, 5: 11, 7: 9, 8: 10, 9: 0, 17: 9}
    while i < len(body):
        kind = int(body[i])
        vals = body[i + 1].split() if sizes[kind] else []
        if len(vals) != sizes[kind]:
            raise ValueError("object %d: %d values" % (kind, len(vals)))
        objs.append((kind, [float(v) for v in vals]))
        i += 2 if sizes[kind] else 1
    return head, objs


def check_r3d(text, ntri):
    try:
        head, objs = r3d_objects(text)
    except (ValueError, KeyError, IndexError) as e:
        R.report(False, "Raster3D: header and object records parse", str(e))
        return
    tiles = [int(x) for x in head[1].split()], [int(x) for x in head[2].split()]
    kinds = [k for k, _ in objs]
    ok = tiles[0][0] * tiles[1][0] == 160 and tiles[0][1] * tiles[1][1] == 120
    ok = ok and head[16:20] == ["3", "*", "*", "*"]
    cone_tris = kinds.count(1) - 1
    R.report(ok and kinds.count(2) == 2 and kinds.count(5) == 1 and kinds.count(3) == 1 and
             kinds.count(7) == kinds.count(1) and cone_tris > 0 and
             kinds.count(8) == kinds.count(9) == 1,
             "Raster3D: header (160x120 in tiles, free-format input), 2 spheres, 1 flat-ended "
             "cylinder, the line as a rounded one, triangles with normals, one material block",
             str({k: kinds.count(k) for k in set(kinds)}))
    R.report(any(k == 2 and v[4:7] == [1, 0, 0] for k, v in objs),
             "Raster3D: the red sphere's colour")


def check_polyhedra(f):
    facets = stl_facets(f["stl"])
    R.report(facets is not None and len(facets) == 24,
             "Polyhedra: octahedron, tetrahedron and cube are 8 + 4 + 12 = 24 triangles",
             "got %s" % (None if facets is None else len(facets)))
    out = 0
    for v, n, o in polyhedra_of(facets or []):
        c = [sum(p[k] for p in v) / 3 for k in range(3)]
        out += sum((c[k] - o[k]) * n[k] for k in range(3)) > 0
    R.report(facets and out == len(facets), "Polyhedra: every face's normal points outwards",
             "%d of %d" % (out, len(facets or [])))
    t = vrml_tokens(f["wrl"])
    R.report(t.count("IndexedFaceSet") == 1 and f["wrl"].count(" -1 ") == 24,
             "Polyhedra: one VRML face set of 24 triangles")


def polyhedra_of(facets):
    """Each facet with the centre of its polyhedron (facets sharing a vertex belong to one;
    the centre is the mean of its distinct vertices)."""
    key = lambda p: tuple(round(x, 4) for x in p)
    parent = {}

    def find(a):
        while parent.setdefault(a, a) != a:
            a = parent[a]
        return a
    for v, _ in facets:
        for p in v[1:]:
            parent[find(key(p))] = find(key(v[0]))
    groups = {}
    for p in parent:
        groups.setdefault(find(p), set()).add(p)
    centre = {g: [sum(p[k] for p in ps) / len(ps) for k in range(3)] for g, ps in groups.items()}
    return [(v, n, centre[find(key(v[0]))]) for v, n in facets]


def read_ppm(data):
    m = re.match(rb"P6\s+(\d+)\s+(\d+)\s+255\s", data)
    return int(m.group(1)), int(m.group(2)), data[m.end():]


def convert(path):
    """ImageMagick's reading of an image file, as 8-bit RGB."""
    p = subprocess.run(["/usr/bin/convert", path, "-depth", "8", "ppm:-"], capture_output=True)
    return read_ppm(p.stdout) if p.returncode == 0 else None


def check_rgb():
    if not os.path.exists("/usr/bin/convert"):
        R.skip("rgb", "ImageMagick's convert is not installed (Debian package imagemagick)")
        return
    from PIL import Image
    devices = ["snapshot", "TachyonInternal", "TachyonLOpenCLInternal"]
    script = SCENE + "\n" + "\n".join(
        "if {![catch {render %s %s/%s.png}]} { render %s %s/%s.rgb }" % (d, OUT, d, d, OUT, d)
        for d in devices)
    run(script)
    for d in devices:
        png, rgb = "%s/%s.png" % (OUT, d), "%s/%s.rgb" % (OUT, d)
        if not os.path.exists(png):
            R.skip("rgb: " + d, "the device does not render here")
            continue
        ident = subprocess.run(["identify", rgb], capture_output=True, text=True).stdout
        back = convert(rgb)
        ref = Image.open(png).convert("RGB")
        R.report(" SGI 160x120 " in ident and back is not None and back[:2] == ref.size and
                 back[2] == ref.tobytes(),
                 "%s: the .rgb is an SGI image ImageMagick reads, the PNG's pixels" % d, ident)


def raster3d_picture(f):
    """Raster3D's render draws the .r3d (as PNG: Debian's is built without SGI output); the
    red sphere lands where the snapshot has it."""
    if not shutil.which("render") or not os.path.exists("%s/snapshot.png" % OUT):
        R.skip("Raster3D render", "Raster3D's render (Debian raster3d) or a snapshot missing")
        return
    from PIL import Image
    path = "%s/scene.r3d" % OUT
    p = subprocess.run("render -png %s.png < %s" % (path, path), shell=True,
                       capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(path + ".png"):
        R.report(False, "Raster3D's render reads the .r3d", (p.stdout + p.stderr)[-300:])
        return
    img = Image.open(path + ".png").convert("RGB")
    back = img.size[0], img.size[1], img.tobytes()
    snap = Image.open("%s/snapshot.png" % OUT).convert("RGB")

    def red_centre(w, h, px):
        pts = [(x, y) for y in range(h) for x in range(w)
               if px(x, y)[0] > 60 and px(x, y)[1] < px(x, y)[0] / 3 and px(x, y)[2] < px(x, y)[0] / 3]
        if not pts:
            return None
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        return ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)    # the disc's centre

    w, h, data = back
    a = red_centre(w, h, lambda x, y: data[3 * (y * w + x):3 * (y * w + x) + 3])
    b = red_centre(160, 120, lambda x, y: snap.getpixel((x, y)))
    R.report(a and b and abs(a[0] - b[0]) < 2 and abs(a[1] - b[1]) < 2 and (w, h) == (160, 120),
             "Raster3D's render draws the .r3d at the display's size, the red sphere where "
             "the snapshot has it", "%s vs %s" % (a, b))


check_scene(export(SCENE, "scene"))
check_polyhedra(export(POLY, "poly"))
check_rgb()
raster3d_picture(None)
sys.exit(1 if R.failures else 0)
