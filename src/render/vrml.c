/* vrml.c: the `VRML-2` and `X3D` devices: the scene as a VRML97 world (.wrl) or the same
 * nodes in X3D's XML encoding (.x3d), in world coordinates, seen from VMD's camera (a
 * Viewpoint at the eye with VMD's perspective field of view; the formats' viewers have
 * no orthographic camera). Spheres are Sphere nodes and cylinders
 * Cylinder nodes in a Transform, pointed cones Cone nodes; a display list's triangles (its
 * meshes and its truncated cones) are one IndexedFaceSet with per-vertex normals and
 * colours, its lines (and text strokes) one IndexedLineSet, its points one PointSet. Each
 * shape carries its material (diffuse, specular, shininess, transparency; unlit lists glow
 * in their colour). The two encodings differ only in syntax: one writer does both. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the two syntaxes */

typedef struct vw {
    FILE *f;
    int x3d;
    int open_tag;                 /* X3D: the last start tag still takes attributes */
    const char *stack[16];
    int depth;
    const ms_scene_item *it;
    /* the list's triangles, segments and points, written when the list ends */
    float *tp, *tn, *lp, *pp;
    ms_rgba8 *tc, *lc, *pc;
    size_t nt, ct, nl, cl, np, cp;
    int oom;
} vw;

/* A node; field is its field name in the parent (VRML's "geometry"), NULL for children. */
static void node(vw *w, const char *field, const char *name)
{
    if (w->x3d) {
        if (w->open_tag) fputs(">", w->f);
        fprintf(w->f, "\n<%s", name);
        w->open_tag = 1;
    } else {
        fprintf(w->f, "\n%s%s%s {", field ? field : "", field ? " " : "", name);
    }
    w->stack[w->depth++] = name;
}

static void end(vw *w)
{
    const char *name = w->stack[--w->depth];
    if (!w->x3d) fputs(" }", w->f);
    else if (w->open_tag) fputs("/>", w->f);
    else fprintf(w->f, "</%s>", name);
    w->open_tag = 0;
}

/* VRML's "children [" ... "]"; nothing in X3D. */
static void children(vw *w, int open)
{
    if (!w->x3d) fputs(open ? " children [" : " ]", w->f);
}

/* A field and its value: name v (VRML, "[v]" when multi) or name='v' (X3D). */
static void field_open(vw *w, const char *name, int multi)
{
    if (w->x3d) fprintf(w->f, " %s='", name);
    else fprintf(w->f, " %s %s", name, multi ? "[ " : "");
}

static void field_close(vw *w, int multi)
{
    if (w->x3d) fputc('\'', w->f);
    else if (multi) fputs(" ]", w->f);
}

static void field3(vw *w, const char *name, float x, float y, float z)
{
    field_open(w, name, 0);
    fprintf(w->f, "%g %g %g", x, y, z);
    field_close(w, 0);
}

static void field1(vw *w, const char *name, float x)
{
    field_open(w, name, 0);
    fprintf(w->f, "%g", x);
    field_close(w, 0);
}

static void field_bool(vw *w, const char *name, int v)
{
    field_open(w, name, 0);
    fputs(w->x3d ? (v ? "true" : "false") : (v ? "TRUE" : "FALSE"), w->f);
    field_close(w, 0);
}

/* ---------------------------------------------------------------- shapes */

/* Shape { appearance Appearance { material Material {...} } ; col NULL: vertex colours. */
static void shape_open(vw *w, const ms_rgba8 *col)
{
    const ms_material *m = &w->it->mat;
    float c[3] = {1, 1, 1};
    if (col) ms_rgba8_to_float(*col, c);
    node(w, NULL, "Shape");
    node(w, "appearance", "Appearance");
    node(w, "material", "Material");
    if (w->it->dl->lit) {
        field3(w, "diffuseColor", c[0] * m->diffuse, c[1] * m->diffuse, c[2] * m->diffuse);
        field1(w, "ambientIntensity", m->ambient);
        field3(w, "specularColor", m->specular, m->specular, m->specular);
        field1(w, "shininess", MS_MIN(1.0f, m->shininess / 128.0f));
    } else {
        field3(w, "diffuseColor", 0, 0, 0);
        field3(w, "emissiveColor", c[0], c[1], c[2]);
    }
    field1(w, "transparency", 1.0f - m->opacity * (col ? col->a / 255.0f : 1.0f));
    end(w);
    end(w);
}

static void transform_open(vw *w, const float t[3], const float axis[3], float angle)
{
    node(w, NULL, "Transform");
    field3(w, "translation", t[0], t[1], t[2]);
    if (axis && angle != 0.0f) {
        field_open(w, "rotation", 0);
        fprintf(w->f, "%g %g %g %g", axis[0], axis[1], axis[2], angle);
        field_close(w, 0);
    }
    children(w, 1);
}

static void transform_close(vw *w)
{
    children(w, 0);
    end(w);
}

static void sphere(void *ud, const float c[3], float r, ms_rgba8 col, int res)
{
    (void)res;
    vw *w = ud;
    transform_open(w, c, NULL, 0);
    shape_open(w, &col);
    node(w, "geometry", "Sphere");
    field1(w, "radius", r);
    end(w);
    end(w);
    transform_close(w);
}

/* The rotation taking +y to the direction a->b; its length in *len. */
static void y_to(const float a[3], const float b[3], float axis[3], float *angle, float *len)
{
    float d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    *len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float inv = *len > 0 ? 1.0f / *len : 0;
    axis[0] = d[2] * inv;
    axis[1] = 0;
    axis[2] = -d[0] * inv;
    float s = sqrtf(axis[0] * axis[0] + axis[2] * axis[2]), cy = d[1] * inv;
    *angle = atan2f(s, cy);
    if (s > 1e-6f) {
        axis[0] /= s;
        axis[2] /= s;
    } else {
        axis[0] = 1;
        axis[2] = 0;
    }
}

/* A Cylinder or a Cone along a->b (VRML's are centred on the origin along +y). */
static void axial(vw *w, const float a[3], const float b[3], ms_rgba8 col, const char *kind,
                  float r, int caps)
{
    float axis[3], angle, len, mid[3];
    y_to(a, b, axis, &angle, &len);
    for (int k = 0; k < 3; k++) mid[k] = 0.5f * (a[k] + b[k]);
    transform_open(w, mid, axis, angle);
    shape_open(w, &col);
    node(w, "geometry", kind);
    field1(w, "height", len);
    field1(w, kind[1] == 'y' ? "radius" : "bottomRadius", r);
    field_bool(w, "bottom", caps & MS_CAP_BASE);
    if (kind[1] == 'y') field_bool(w, "top", caps & MS_CAP_APEX);
    end(w);
    end(w);
    transform_close(w);
}

static void cylinder(void *ud, const float a[3], const float b[3], float r, ms_rgba8 col,
                     int caps, int res)
{
    (void)res;
    axial(ud, a, b, col, "Cylinder", r, caps);
}

static void triangle(void *ud, const float p[9], const float n[9], const ms_rgba8 c[3]);

typedef struct tess_ctx {
    vw *w;
    ms_rgba8 col;
} tess_ctx;

static void tess_tri(void *ud, const float p[9], const float n[9])
{
    tess_ctx *t = ud;
    ms_rgba8 c[3] = {t->col, t->col, t->col};
    triangle(t->w, p, n, c);
}

static void cone(void *ud, const float base[3], const float apex[3], float rb, float ra,
                 ms_rgba8 col, int res)
{
    if (ra == 0.0f) {
        axial(ud, base, apex, col, "Cone", rb, MS_CAP_BASE);
        return;
    }
    tess_ctx t = {ud, col};
    ms_tess_cone(base, apex, rb, ra, res, MS_CAP_BASE, tess_tri, &t);
}

/* ---------------------------------------------------------------- per-list sets */

/* Append k vertices (3k floats, k colours) to a buffer; 0, or -1 when memory runs out. */
static int push(vw *w, float **p, ms_rgba8 **c, size_t *n, size_t *cap, const float *xyz,
                const ms_rgba8 *col, int k)
{
    size_t cp = *cap;
    if (*n + (size_t)k > *cap) {
        if (ms_grow((void **)p, &cp, *n + (size_t)k, 3 * sizeof **p) ||
            ms_grow((void **)c, cap, *n + (size_t)k, sizeof **c)) {
            w->oom = 1;
            return -1;
        }
    }
    memcpy(*p + 3 * *n, xyz, 3 * sizeof(float) * (size_t)k);
    memcpy(*c + *n, col, sizeof(ms_rgba8) * (size_t)k);
    *n += (size_t)k;
    return 0;
}

static void triangle(void *ud, const float p[9], const float n[9], const ms_rgba8 c[3])
{
    vw *w = ud;
    size_t ct = w->ct, before = w->nt;
    if (push(w, &w->tp, &w->tc, &w->nt, &w->ct, p, c, 3)) return;
    if (w->ct != ct) {
        float *nn = realloc(w->tn, 3 * sizeof(float) * w->ct);
        if (!nn) {
            w->oom = 1;
            w->nt = before;
            return;
        }
        w->tn = nn;
    }
    memcpy(w->tn + 3 * before, n, 9 * sizeof(float));
}

static void line(void *ud, const float a[3], const float b[3], ms_rgba8 col)
{
    vw *w = ud;
    float p[6] = {a[0], a[1], a[2], b[0], b[1], b[2]};
    ms_rgba8 c[2] = {col, col};
    push(w, &w->lp, &w->lc, &w->nl, &w->cl, p, c, 2);
}

static void point(void *ud, const float c[3], ms_rgba8 col)
{
    vw *w = ud;
    push(w, &w->pp, &w->pc, &w->np, &w->cp, c, &col, 1);
}

static void floats(vw *w, const char *name, const float *v, size_t n)
{
    field_open(w, name, 1);
    for (size_t i = 0; i < n; i++)
        fprintf(w->f, "%s%g %g %g", i ? ", " : "", v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    field_close(w, 1);
}

static void colors(vw *w, const ms_rgba8 *c, size_t n)
{
    node(w, "color", "Color");
    field_open(w, "color", 1);
    for (size_t i = 0; i < n; i++) {
        float f[3];
        ms_rgba8_to_float(c[i], f);
        fprintf(w->f, "%s%.3f %.3f %.3f", i ? ", " : "", f[0], f[1], f[2]);
    }
    field_close(w, 1);
    end(w);
}

/* Coordinate indices 0 .. n-1 in groups of k, each ended by -1. */
static void indices(vw *w, size_t n, int k)
{
    field_open(w, "coordIndex", 1);
    for (size_t i = 0; i < n; i++)
        fprintf(w->f, "%zu%s", i, (int)(i % (size_t)k) == k - 1 ? " -1 " : " ");
    field_close(w, 1);
}

/* X3D puts a set's index fields on its start tag, before its Coordinate; VRML anywhere. */
static void vertex_set(vw *w, const char *kind, const float *p, const float *n,
                       const ms_rgba8 *c, size_t count, int k)
{
    shape_open(w, NULL);
    node(w, "geometry", kind);
    if (k > 1) indices(w, count, k);
    if (k == 3) field_bool(w, "solid", 0);
    node(w, "coord", "Coordinate");
    floats(w, "point", p, count);
    end(w);
    if (n) {
        node(w, "normal", "Normal");
        floats(w, "vector", n, count);
        end(w);
    }
    colors(w, c, count);
    end(w);
    end(w);
}

static void item_begin(void *ud, const ms_scene_item *it)
{
    vw *w = ud;
    w->it = it;
    w->nt = w->nl = w->np = 0;
}

static void item_end(void *ud, const ms_scene_item *it)
{
    (void)it;
    vw *w = ud;
    if (w->nt) vertex_set(w, "IndexedFaceSet", w->tp, w->tn, w->tc, w->nt, 3);
    if (w->nl) vertex_set(w, "IndexedLineSet", w->lp, NULL, w->lc, w->nl, 2);
    if (w->np) vertex_set(w, "PointSet", w->pp, NULL, w->pc, w->np, 1);
}

/* ---------------------------------------------------------------- the file */

static void viewpoint(vw *w, const ms_scene *s)
{
    const ms_camera *cam = &s->settings.cam;
    float d = cam->eye[2] - cam->distance, half = 0.5f * cam->height;
    /* VRML's field of view is the angle of the image's smaller side */
    if (s->width < s->height) half *= (float)s->width / (float)s->height;
    node(w, NULL, "Viewpoint");
    field3(w, "position", cam->eye[0], cam->eye[1], cam->eye[2]);
    field1(w, "fieldOfView", 2.0f * atanf(half / (d > 0 ? d : 1.0f)));
    end(w);
    node(w, NULL, "Background");
    field_open(w, "skyColor", 1);
    fprintf(w->f, "%g %g %g", s->background[0], s->background[1], s->background[2]);
    field_close(w, 1);
    end(w);
}

static void header(vw *w, const ms_scene *s)
{
    if (w->x3d) {
        fprintf(w->f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<!DOCTYPE X3D PUBLIC \"ISO//Web3D//DTD X3D 3.0//EN\" "
                      "\"http://www.web3d.org/specifications/x3d-3.0.dtd\">\n"
                      "<X3D profile='Interchange' version='3.0'>\n<head>\n"
                      "<meta name='generator' content='molscope %s'/>\n</head>\n<Scene>",
                PACKAGE_VERSION);
    } else {
        fprintf(w->f, "#VRML V2.0 utf8\n# written by molscope %s\n", PACKAGE_VERSION);
    }
    viewpoint(w, s);
}

static int body(const ms_scene *s, FILE *f, int x3d, ms_error *err)
{
    static const ms_export_visitor v = {
        .item = item_begin, .item_end = item_end, .sphere = sphere, .cylinder = cylinder,
        .cone = cone, .triangle = triangle, .line = line, .point = point};
    vw w;
    memset(&w, 0, sizeof w);
    w.f = f;
    w.x3d = x3d;
    header(&w, s);
    ms_export_walk(s, &v, &w);
    fputs(x3d ? "\n</Scene>\n</X3D>\n" : "\n", f);
    free(w.tp), free(w.tn), free(w.tc), free(w.lp), free(w.lc), free(w.pp), free(w.pc);
    if (w.oom) ms_error_set(err, "out of memory");
    return w.oom ? -1 : 0;
}

static int vrml_body(const ms_scene *s, FILE *f, void *user, ms_error *err)
{
    (void)user;
    return body(s, f, 0, err);
}

static int x3d_body(const ms_scene *s, FILE *f, void *user, ms_error *err)
{
    (void)user;
    return body(s, f, 1, err);
}

static int write_vrml(const ms_scene *s, const char *path, ms_error *err)
{
    return ms_export_file(s, path, vrml_body, NULL, err);
}

static int write_x3d(const ms_scene *s, const char *path, ms_error *err)
{
    return ms_export_file(s, path, x3d_body, NULL, err);
}

const ms_render_device ms_render_vrml2 = {
    .name = "VRML-2",
    .description = "VRML 2.0 (VRML97) world",
    .default_cmd = "true",
    .write = write_vrml};

const ms_render_device ms_render_x3d = {
    .name = "X3D",
    .description = "X3D world (XML encoding)",
    .default_cmd = "true",
    .write = write_x3d};
