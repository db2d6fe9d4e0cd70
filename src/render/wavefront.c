/* wavefront.c: the `Wavefront` device: the scene as a Wavefront OBJ file and its MTL
 * material library (file.obj and file.mtl), in world coordinates. Spheres, cylinders and
 * cones are tessellated; meshes keep their vertices and normals; lines, points and text are
 * OBJ lines and points. OBJ colours are per face, so each distinct (colour, material,
 * lighting) gets a material; a mesh face takes the average of its vertex colours. OBJ has no
 * clip planes: a list cut by clip planes has its triangles and lines cut (render/clip.c). */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct mtl {
    uint64_t key;
    ms_rgba8 color;
    ms_material mat;   /* name not owned */
    int lit;
} mtl;

typedef struct obj {
    FILE *f;
    const ms_scene_item *it;
    size_t nv, nn;              /* vertices and normals written so far */
    mtl *mtls;
    size_t nmtls, capmtls;
    size_t *slots;              /* open-addressing table of mtl index + 1 */
    size_t nslots;
    long current;               /* material of the faces being written */
    int lit;
    ms_rgba8 color;
    int oom;
} obj;

static uint64_t mtl_key(ms_rgba8 c, int matid, int lit)
{
    uint32_t rgba = (uint32_t)c.r | (uint32_t)c.g << 8 | (uint32_t)c.b << 16 | (uint32_t)c.a << 24;
    return (uint64_t)rgba | (uint64_t)(uint32_t)(matid & 0x7fffffff) << 32 | (uint64_t)(lit != 0) << 63;
}

static int rehash(obj *o)
{
    size_t n = o->nslots ? 2 * o->nslots : 256;
    size_t *s = calloc(n, sizeof *s);
    if (!s) return -1;
    for (size_t i = 0; i < o->nmtls; i++) {
        size_t h = (size_t)(o->mtls[i].key * 0x9E3779B97F4A7C15ull) & (n - 1);
        while (s[h]) h = (h + 1) & (n - 1);
        s[h] = i + 1;
    }
    free(o->slots);
    o->slots = s;
    o->nslots = n;
    return 0;
}

/* Index of the material for a colour in the current item, added when new; -1 on no memory. */
static long mtl_of(obj *o, ms_rgba8 c, int lit)
{
    uint64_t key = mtl_key(c, o->it->mat.id, lit);
    if ((o->nmtls + 1) * 2 > o->nslots && rehash(o)) return -1;
    size_t h = (size_t)(key * 0x9E3779B97F4A7C15ull) & (o->nslots - 1);
    while (o->slots[h]) {
        if (o->mtls[o->slots[h] - 1].key == key) return (long)o->slots[h] - 1;
        h = (h + 1) & (o->nslots - 1);
    }
    if (ms_grow((void **)&o->mtls, &o->capmtls, o->nmtls + 1, sizeof *o->mtls)) return -1;
    mtl *m = &o->mtls[o->nmtls];
    m->key = key;
    m->color = c;
    m->mat = o->it->mat;
    m->lit = lit;
    o->slots[h] = ++o->nmtls;
    return (long)o->nmtls - 1;
}

static void mtl_name(FILE *f, const mtl *m)
{
    fprintf(f, "ms_%d_%02x%02x%02x%02x%s", m->mat.id, m->color.r, m->color.g, m->color.b,
            m->color.a, m->lit ? "" : "_flat");
}

static void use(obj *o, ms_rgba8 c, int lit)
{
    long m = mtl_of(o, c, lit);
    if (m < 0) {
        o->oom = 1;
        return;
    }
    if (m == o->current) return;
    o->current = m;
    fputs("usemtl ", o->f);
    mtl_name(o->f, &o->mtls[m]);
    fputc('\n', o->f);
}

/* "v x y z\n" */
static void vertex(FILE *f, const float *p)
{
    char b[100];
    int n = 2;
    b[0] = 'v';
    b[1] = ' ';
    for (int k = 0; k < 3; k++) {
        n += ms_fmt_g(b + n, p[k]);
        b[n++] = k < 2 ? ' ' : '\n';
    }
    fwrite(b, 1, (size_t)n, f);
}

static void tri_out(void *ud, const float p[9], const float n[9])
{
    obj *o = ud;
    for (int k = 0; k < 3; k++) vertex(o->f, p + 3 * k);
    for (int k = 0; k < 3; k++)
        fprintf(o->f, "vn %.4f %.4f %.4f\n", n[3 * k], n[3 * k + 1], n[3 * k + 2]);
    fprintf(o->f, "f %zu//%zu %zu//%zu %zu//%zu\n", o->nv + 1, o->nn + 1, o->nv + 2, o->nn + 2,
            o->nv + 3, o->nn + 3);
    o->nv += 3;
    o->nn += 3;
}

static void tri(void *ud, const float p[9], const float n[9])
{
    obj *o = ud;
    ms_export_clip_tri(o->it, p, n, tri_out, o);
}

static void seg(void *ud, const float a0[3], const float b0[3])
{
    obj *o = ud;
    float a[3] = {a0[0], a0[1], a0[2]}, b[3] = {b0[0], b0[1], b0[2]};
    if (!ms_export_clip_seg(o->it, a, b)) return;
    fprintf(o->f, "v %g %g %g\nv %g %g %g\nl %zu %zu\n", a[0], a[1], a[2], b[0], b[1], b[2],
            o->nv + 1, o->nv + 2);
    o->nv += 2;
}

static void solids(obj *o, const ms_displaylist *dl, float scale)
{
    const float *m = o->it->xform;
    for (size_t i = 0; i < dl->spheres.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->spheres.xyz + 3 * i, c);
        use(o, dl->spheres.color[i], dl->lit);
        ms_tess_sphere(c, dl->spheres.radius[i] * scale, dl->spheres.res[i], tri, o);
    }
    ms_dl_pieces it = ms_dl_pieces_of(&dl->cylinders);
    ms_dl_piece p;
    while (ms_dl_pieces_next(&it, &p)) {
        float a[3], b[3], r = p.radius * scale;
        ms_mat4_point(m, p.a, a);
        ms_mat4_point(m, p.b, b);
        use(o, p.color, dl->lit);
        ms_tess_cone(a, b, r, r, p.res, p.caps, tri, o);
    }
    const ms_dl_cones *co = &dl->cones;
    for (size_t i = 0; i < co->n; i++) {
        float a[3], b[3];
        ms_mat4_point(m, co->base + 3 * i, a);
        ms_mat4_point(m, co->apex + 3 * i, b);
        use(o, co->color[i], dl->lit);
        ms_tess_cone(a, b, co->rbase[i] * scale, co->rapex[i] * scale, co->res[i], MS_CAP_BASE,
                     tri, o);
    }
}

static ms_rgba8 average(const ms_rgba8 *c, const uint32_t *v)
{
    unsigned r = 0, g = 0, b = 0, a = 0;
    for (int k = 0; k < 3; k++) {
        r += c[v[k]].r;
        g += c[v[k]].g;
        b += c[v[k]].b;
        a += c[v[k]].a;
    }
    return (ms_rgba8){(uint8_t)((r + 1) / 3), (uint8_t)((g + 1) / 3), (uint8_t)((b + 1) / 3),
                      (uint8_t)((a + 1) / 3)};
}

/* A mesh that clip planes cut: each triangle on its own, cut. */
static void clipped_mesh(obj *o, const ms_displaylist *dl)
{
    const ms_dl_mesh *ms = &dl->mesh;
    const float *m = o->it->xform;
    for (size_t t = 0; t < ms->ntris; t++) {
        float p[9], n[9];
        ms_export_mesh_tri(ms, t, m, p, n);
        use(o, average(ms->color, ms->tri + 3 * t), dl->lit);
        tri(o, p, n);
    }
}

static void mesh(obj *o, const ms_displaylist *dl)
{
    const ms_dl_mesh *ms = &dl->mesh;
    if (!ms->ntris || !ms->nverts) return;
    if (o->it->nclip) {
        clipped_mesh(o, dl);
        return;
    }
    const float *m = o->it->xform;
    for (size_t i = 0; i < ms->nverts; i++) {
        float p[3], n[3], q[3];
        ms_mat4_point(m, ms->xyz + 3 * i, p);
        for (int k = 0; k < 3; k++) n[k] = ms_normal_dequantize(ms->normal[3 * i + k]);
        ms_mat4_normal(m, n, q);
        vertex(o->f, p);
        fprintf(o->f, "vn %.4f %.4f %.4f\n", q[0], q[1], q[2]);
    }
    for (size_t t = 0; t < ms->ntris; t++) {
        const uint32_t *v = ms->tri + 3 * t;
        use(o, average(ms->color, v), dl->lit);
        fprintf(o->f, "f %zu//%zu %zu//%zu %zu//%zu\n", o->nv + v[0] + 1, o->nn + v[0] + 1,
                o->nv + v[1] + 1, o->nn + v[1] + 1, o->nv + v[2] + 1, o->nn + v[2] + 1);
    }
    o->nv += ms->nverts;
    o->nn += ms->nverts;
}

static void thin(obj *o, const ms_displaylist *dl)
{
    const float *m = o->it->xform;
    for (size_t i = 0; i < dl->lines.n; i++) {
        float a[3], b[3];
        ms_mat4_point(m, dl->lines.a + 3 * i, a);
        ms_mat4_point(m, dl->lines.b + 3 * i, b);
        use(o, dl->lines.color[i], 0);
        if (dl->lines.style[i] == MS_LINE_DASHED) ms_export_dashes(a, b, seg, o);
        else seg(o, a, b);
    }
    for (size_t i = 0; i < dl->points.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->points.xyz + 3 * i, c);
        if (ms_scene_clipped(o->it, c)) continue;
        use(o, dl->points.color[i], 0);
        fprintf(o->f, "v %g %g %g\np %zu\n", c[0], c[1], c[2], ++o->nv);
    }
    for (size_t i = 0; i < dl->texts.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->texts.xyz + 3 * i, c);
        use(o, dl->texts.color[i], 0);
        ms_export_text(dl->texts.chars + dl->texts.start[i], c, dl->texts.size[i], seg, o);
    }
}

static void write_mtl(FILE *f, const obj *o)
{
    fprintf(f, "# Wavefront MTL file exported from molscope %s\n", PACKAGE_VERSION);
    for (size_t i = 0; i < o->nmtls; i++) {
        const mtl *m = &o->mtls[i];
        float c[3];
        ms_rgba8_to_float(m->color, c);
        fputs("\nnewmtl ", f);
        mtl_name(f, m);
        fputc('\n', f);
        float op = m->mat.opacity * (m->color.a / 255.0f);
        if (!m->lit) {
            fprintf(f, "Kd %.3f %.3f %.3f\nd %g\nillum 0\n", c[0], c[1], c[2], op);
            continue;
        }
        float a = m->mat.ambient, d = m->mat.diffuse, s = m->mat.specular;
        fprintf(f, "Ka %.3f %.3f %.3f\nKd %.3f %.3f %.3f\nKs %.3f %.3f %.3f\n", a * c[0],
                a * c[1], a * c[2], d * c[0], d * c[1], d * c[2], s, s, s);
        fprintf(f, "Ns %g\nd %g\nillum 2\n", MS_MIN(1000.0f, m->mat.shininess), op);
    }
}

/* file.obj -> file.mtl; other names get .mtl appended. */
static char *mtl_path(const char *path)
{
    size_t n = strlen(path);
    char *p = malloc(n + 5);
    if (!p) return NULL;
    memcpy(p, path, n + 1);
    if (n > 4 && !strcasecmp(p + n - 4, ".obj")) memcpy(p + n - 4, ".mtl", 5);
    else memcpy(p + n, ".mtl", 5);
    return p;
}

/* Put the pair in place once both are written and flushed, the .mtl first: a failure
 * before that leaves both files as they were. 0, or -1 with err set. */
static int commit_pair(ms_ofile *obj_out, ms_ofile *mtl_out, int ok, ms_error *err)
{
    ok = ok && ms_ofile_check(mtl_out, err) == 0 && ms_ofile_check(obj_out, err) == 0;
    if (ok && ms_ofile_commit(mtl_out, err) == 0) return ms_ofile_commit(obj_out, err);
    if (!ok) ms_ofile_abort(mtl_out);
    ms_ofile_abort(obj_out);
    return -1;
}

static int write_obj(const ms_scene *s, const char *path, ms_error *err)
{
    char *mpath = mtl_path(path);
    if (!mpath) {
        ms_error_set(err, "%s: out of memory", path);
        return -1;
    }
    ms_ofile *out, *mout = NULL;
    FILE *f = ms_ofile_open_stream(path, &out, err);
    if (!f) {
        free(mpath);
        return -1;
    }
    obj o;
    memset(&o, 0, sizeof o);
    o.f = f;
    const char *base = strrchr(mpath, '/');
    fprintf(f, "# Wavefront OBJ file exported from molscope %s\nmtllib %s\n", PACKAGE_VERSION,
            base ? base + 1 : mpath);
    for (size_t i = 0; i < s->nitems && !o.oom; i++) {
        o.it = &s->items[i];
        o.current = -1;
        fprintf(f, "g list%zu\n", i);
        solids(&o, o.it->dl, ms_item_scale(o.it));
        mesh(&o, o.it->dl);
        thin(&o, o.it->dl);
    }
    FILE *mf = o.oom ? NULL : ms_ofile_open_stream(mpath, &mout, err);
    if (mf) write_mtl(mf, &o);
    else if (o.oom) ms_error_set(err, "%s: out of memory", path);
    int rc = commit_pair(out, mout, mf != NULL, err);
    free(o.mtls);
    free(o.slots);
    free(mpath);
    return rc;
}

const ms_render_device ms_render_wavefront = {
    .name = "Wavefront",
    .description = "Wavefront OBJ and MTL files",
    .default_cmd = "true",
    .write = write_obj};
