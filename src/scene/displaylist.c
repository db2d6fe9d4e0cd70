/* displaylist.c: growing the structure-of-arrays primitive columns, appending primitives,
 * walking a list's cylinders as VMD's pieces (a bond's two halves), counting and bounding. */
#include "config.h"
#include "scene/displaylist.h"
#include "vecmath/vecf.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

static atomic_ulong next_gen = 1;

static unsigned long new_gen(void) { return atomic_fetch_add(&next_gen, 1); }

/* A set of parallel arrays sharing one count and capacity. */
typedef struct column {
    void **ptr;
    size_t elsize;
} column;

#define MAX_COLS 8

/* Grow every column to hold need items. On failure the columns that were already grown stay
 * grown (harmless) and *cap is unchanged, so the arrays remain consistent. */
static int grow_columns(size_t *cap, size_t need, const column *cols, int ncols)
{
    if (need <= *cap) return 0;
    size_t ncap = *cap ? *cap : 64;
    while (ncap < need) {
        if (ncap > SIZE_MAX / 2) return -1;
        ncap *= 2;
    }
    for (int i = 0; i < ncols; i++) {
        size_t bytes;
        if (ms_mul_size(ncap, cols[i].elsize, &bytes)) return -1;
        void *p = realloc(*cols[i].ptr, bytes);
        if (!p) return -1;
        *cols[i].ptr = p;
    }
    *cap = ncap;
    return 0;
}

/* The columns of one kind, and its count and capacity. */
static int kind_columns(ms_displaylist *dl, ms_dl_kind kind, column *c, size_t **n, size_t **cap)
{
    int k = 0;
#define COL(field, size) (c[k].ptr = (void **)&(field), c[k].elsize = (size), k++)
    switch (kind) {
    case MS_DL_SPHERES: {
        ms_dl_spheres *s = &dl->spheres;
        COL(s->xyz, 3 * sizeof(float)); COL(s->radius, sizeof(float));
        COL(s->color, sizeof(ms_rgba8)); COL(s->res, sizeof(uint16_t));
        *n = &s->n; *cap = &s->cap;
        break;
    }
    case MS_DL_CYLINDERS: {
        ms_dl_cylinders *s = &dl->cylinders;
        COL(s->base, 3 * sizeof(float)); COL(s->apex, 3 * sizeof(float));
        COL(s->joint, 3 * sizeof(float)); COL(s->radius, sizeof(float));
        COL(s->color, sizeof(ms_rgba8)); COL(s->color2, sizeof(ms_rgba8));
        COL(s->flags, 1); COL(s->res, sizeof(uint16_t));
        *n = &s->n; *cap = &s->cap;
        s->norder = 0;          /* claiming cylinders drops the pieces' order */
        break;
    }
    case MS_DL_CONES: {
        ms_dl_cones *s = &dl->cones;
        COL(s->base, 3 * sizeof(float)); COL(s->apex, 3 * sizeof(float));
        COL(s->rbase, sizeof(float)); COL(s->rapex, sizeof(float));
        COL(s->color, sizeof(ms_rgba8)); COL(s->res, sizeof(uint16_t));
        *n = &s->n; *cap = &s->cap;
        break;
    }
    case MS_DL_LINES: {
        ms_dl_lines *s = &dl->lines;
        COL(s->a, 3 * sizeof(float)); COL(s->b, 3 * sizeof(float));
        COL(s->width, sizeof(float)); COL(s->color, sizeof(ms_rgba8)); COL(s->style, 1);
        *n = &s->n; *cap = &s->cap;
        break;
    }
    case MS_DL_POINTS: {
        ms_dl_points *s = &dl->points;
        COL(s->xyz, 3 * sizeof(float)); COL(s->size, sizeof(float));
        COL(s->color, sizeof(ms_rgba8));
        *n = &s->n; *cap = &s->cap;
        break;
    }
    case MS_DL_TEXTS: {
        ms_dl_texts *s = &dl->texts;
        COL(s->xyz, 3 * sizeof(float)); COL(s->size, sizeof(float));
        COL(s->thickness, sizeof(float)); COL(s->color, sizeof(ms_rgba8));
        COL(s->start, sizeof(uint32_t));
        *n = &s->n; *cap = &s->cap;
        break;
    }
    default:
        return 0;
    }
#undef COL
    return k;
}

void ms_dl_init(ms_displaylist *dl)
{
    memset(dl, 0, sizeof *dl);
    dl->lit = 1;
    ms_mat4_identity(dl->model);
    dl->gen = new_gen();
}

void ms_dl_free(ms_displaylist *dl)
{
    column c[MAX_COLS];
    size_t *n, *cap;
    for (int kind = 0; kind < MS_DL_NKINDS; kind++) {
        int k = kind_columns(dl, (ms_dl_kind)kind, c, &n, &cap);
        for (int i = 0; i < k; i++) {
            free(*c[i].ptr);
            *c[i].ptr = NULL;
        }
        *n = *cap = 0;
    }
    free(dl->texts.chars);
    free(dl->cylinders.order);
    dl->cylinders.order = NULL;
    dl->cylinders.norder = dl->cylinders.ordercap = 0;
    free(dl->mesh.xyz);
    free(dl->mesh.normal);
    free(dl->mesh.color);
    free(dl->mesh.tri);
    int material = dl->material, lit = dl->lit;
    float model[16];
    memcpy(model, dl->model, sizeof model);
    ms_dl_init(dl);
    dl->material = material;
    dl->lit = lit;
    memcpy(dl->model, model, sizeof model);
}

void ms_dl_clear(ms_displaylist *dl)
{
    dl->spheres.n = dl->cylinders.n = dl->cones.n = 0;
    dl->cylinders.norder = 0;
    dl->lines.n = dl->points.n = dl->texts.n = 0;
    dl->texts.nchars = 0;
    dl->mesh.nverts = dl->mesh.ntris = 0;
    dl->gen = new_gen();
}

static int oom(ms_error *err)
{
    ms_error_set(err, "out of memory for display list");
    return -1;
}

void ms_dl_mesh_adopt(ms_displaylist *dl, float *xyz, int8_t *normal, ms_rgba8 *color,
                      size_t nverts, size_t vcap, uint32_t *tri, size_t ntris)
{
    ms_dl_mesh *m = &dl->mesh;
    free(m->xyz);
    free(m->normal);
    free(m->color);
    free(m->tri);
    m->xyz = xyz;
    m->normal = normal;
    m->color = color;
    m->tri = tri;
    m->nverts = nverts;
    m->vcap = MS_MAX(vcap, nverts);
    m->ntris = m->tcap = ntris;
    dl->gen = new_gen();
}

int ms_dl_reserve(ms_displaylist *dl, ms_dl_kind kind, size_t n, ms_error *err)
{
    column c[MAX_COLS];
    size_t *cnt, *cap;
    int k = kind_columns(dl, kind, c, &cnt, &cap);
    if (k == 0) return 0;
    if (*cnt > SIZE_MAX - n || grow_columns(cap, *cnt + n, c, k)) return oom(err);
    return 0;
}

static int mesh_grow(ms_dl_mesh *m, size_t nverts, size_t ntris)
{
    column v[3] = {{(void **)&m->xyz, 3 * sizeof(float)},
                   {(void **)&m->normal, 3 * sizeof(int8_t)},
                   {(void **)&m->color, sizeof(ms_rgba8)}};
    column t[1] = {{(void **)&m->tri, 3 * sizeof(uint32_t)}};
    if (m->nverts > SIZE_MAX - nverts || m->ntris > SIZE_MAX - ntris) return -1;
    /* Indices are 32-bit. */
    if (m->nverts + nverts > UINT32_MAX) return -1;
    /* one vertex to spare: a ray tracer shares xyz with Embree, which reads 16 bytes a vertex */
    return grow_columns(&m->vcap, m->nverts + nverts + 1, v, 3) ||
           grow_columns(&m->tcap, m->ntris + ntris, t, 1) ? -1 : 0;
}

int ms_dl_mesh_reserve(ms_displaylist *dl, size_t nverts, size_t ntris, ms_error *err)
{
    return mesh_grow(&dl->mesh, nverts, ntris) ? oom(err) : 0;
}

long ms_dl_extend(ms_displaylist *dl, ms_dl_kind kind, size_t count, ms_error *err)
{
    column c[MAX_COLS];
    size_t *cnt, *cap;
    int k = kind_columns(dl, kind, c, &cnt, &cap);
    if (k == 0 || kind == MS_DL_TEXTS) {
        ms_error_set(err, "texts cannot be claimed in blocks");
        return -1;
    }
    if (*cnt > SIZE_MAX - count || grow_columns(cap, *cnt + count, c, k)) return oom(err);
    long first = (long)*cnt;
    *cnt += count;
    return first;
}

int ms_dl_mesh_extend(ms_displaylist *dl, size_t nverts, size_t ntris, size_t *v0, size_t *t0,
                      ms_error *err)
{
    if (mesh_grow(&dl->mesh, nverts, ntris)) return oom(err);
    *v0 = dl->mesh.nverts;
    *t0 = dl->mesh.ntris;
    dl->mesh.nverts += nverts;
    dl->mesh.ntris += ntris;
    return 0;
}

/* Make room for one more primitive of a kind; returns its index or -1. */
static long one_more(ms_displaylist *dl, ms_dl_kind kind)
{
    column c[MAX_COLS];
    size_t *cnt, *cap;
    int k = kind_columns(dl, kind, c, &cnt, &cap);
    if (*cnt == *cap && grow_columns(cap, *cnt + 1, c, k)) return -1;
    return (long)(*cnt)++;
}

static inline void copy3(float *dst, const float *src)
{
    dst[0] = src[0];
    dst[1] = src[1];
    dst[2] = src[2];
}

static uint16_t clamp_res(int res)
{
    return (uint16_t)(res < 0 ? 0 : res > 65535 ? 65535 : res);
}

int ms_dl_sphere(ms_displaylist *dl, const float c[3], float r, ms_rgba8 col, int res)
{
    long i = one_more(dl, MS_DL_SPHERES);
    if (i < 0) return -1;
    ms_dl_spheres *s = &dl->spheres;
    copy3(s->xyz + 3 * i, c);
    s->radius[i] = r;
    s->color[i] = col;
    s->res[i] = clamp_res(res);
    return 0;
}

int ms_dl_cylinder(ms_displaylist *dl, const float a[3], const float b[3], float r, ms_rgba8 col,
                   int caps, int res)
{
    long i = one_more(dl, MS_DL_CYLINDERS);
    if (i < 0) return -1;
    ms_dl_cylinders *s = &dl->cylinders;
    float mid[3] = {0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2])};
    copy3(s->base + 3 * i, a);
    copy3(s->apex + 3 * i, b);
    copy3(s->joint + 3 * i, mid);
    s->radius[i] = r;
    s->color[i] = s->color2[i] = col;
    s->flags[i] = (uint8_t)(caps & MS_CAP_MASK);
    s->res[i] = clamp_res(res);
    return 0;
}

int ms_dl_bond(ms_displaylist *dl, const float a[3], const float j[3], const float b[3], float r,
               ms_rgba8 c1, ms_rgba8 c2, int flags, int res)
{
    long i = one_more(dl, MS_DL_CYLINDERS);
    if (i < 0) return -1;
    ms_dl_cylinders *s = &dl->cylinders;
    copy3(s->base + 3 * i, a);
    copy3(s->apex + 3 * i, b);
    copy3(s->joint + 3 * i, j);
    s->radius[i] = r;
    s->color[i] = c1;
    s->color2[i] = c2;
    s->flags[i] = (uint8_t)((flags & (MS_CAP_MASK | MS_CYL_INWARD)) | MS_CYL_BOND);
    s->res[i] = clamp_res(res);
    return 0;
}

uint32_t *ms_dl_cylinder_order(ms_displaylist *dl, size_t n, ms_error *err)
{
    ms_dl_cylinders *s = &dl->cylinders;
    column c = {(void **)&s->order, sizeof(uint32_t)};
    if (grow_columns(&s->ordercap, n ? n : 1, &c, 1)) {
        oom(err);
        return NULL;
    }
    s->norder = n;
    return s->order;
}

/* ---------------------------------------------------------------- pieces */

/* Half h (0 the base's, 1 the apex's) of cylinder i. */
static void piece(const ms_dl_cylinders *c, size_t i, int h, ms_dl_piece *p)
{
    int f = c->flags[i];
    p->radius = c->radius[i];
    p->res = c->res[i];
    p->cylinder = i;
    if (!(f & MS_CYL_BOND)) {
        p->a = c->base + 3 * i, p->b = c->apex + 3 * i;
        p->color = c->color[i];
        p->caps = f & MS_CAP_MASK;
        return;
    }
    const float *end = (h ? c->apex : c->base) + 3 * i, *joint = c->joint + 3 * i;
    int closed = f & (h ? MS_CAP_APEX : MS_CAP_BASE);
    p->color = h ? c->color2[i] : c->color[i];
    if (h && !(f & MS_CYL_INWARD)) {
        p->a = joint, p->b = end;
        p->caps = closed ? MS_CAP_APEX : 0;
    } else {
        p->a = end, p->b = joint;
        p->caps = closed ? MS_CAP_BASE : 0;
    }
}

int ms_dl_pieces_next(ms_dl_pieces *it, ms_dl_piece *p)
{
    const ms_dl_cylinders *c = it->cy;
    if (c->norder) {
        if (it->next >= c->norder) return 0;
        uint32_t e = c->order[it->next++];
        piece(c, e / 2, (int)(e & 1), p);
        return 1;
    }
    size_t i = it->next / 2;
    if (i >= c->n) return 0;
    int h = (int)(it->next & 1);
    piece(c, i, h, p);
    it->next = h || !(c->flags[i] & MS_CYL_BOND) ? 2 * i + 2 : 2 * i + 1;
    return 1;
}

size_t ms_dl_piece_count(const ms_dl_cylinders *cy)
{
    if (cy->norder) return cy->norder;
    size_t n = cy->n;
    for (size_t i = 0; i < cy->n; i++) n += (cy->flags[i] & MS_CYL_BOND) != 0;
    return n;
}

int ms_dl_cone(ms_displaylist *dl, const float base[3], const float apex[3], float rbase,
               float rapex, ms_rgba8 col, int res)
{
    long i = one_more(dl, MS_DL_CONES);
    if (i < 0) return -1;
    ms_dl_cones *s = &dl->cones;
    copy3(s->base + 3 * i, base);
    copy3(s->apex + 3 * i, apex);
    s->rbase[i] = rbase;
    s->rapex[i] = rapex;
    s->color[i] = col;
    s->res[i] = clamp_res(res);
    return 0;
}

int ms_dl_line(ms_displaylist *dl, const float a[3], const float b[3], float width, ms_rgba8 col,
               int style)
{
    long i = one_more(dl, MS_DL_LINES);
    if (i < 0) return -1;
    ms_dl_lines *s = &dl->lines;
    copy3(s->a + 3 * i, a);
    copy3(s->b + 3 * i, b);
    s->width[i] = width;
    s->color[i] = col;
    s->style[i] = (uint8_t)style;
    return 0;
}

int ms_dl_point(ms_displaylist *dl, const float p[3], float size, ms_rgba8 col)
{
    long i = one_more(dl, MS_DL_POINTS);
    if (i < 0) return -1;
    copy3(dl->points.xyz + 3 * i, p);
    dl->points.size[i] = size;
    dl->points.color[i] = col;
    return 0;
}

int ms_dl_text(ms_displaylist *dl, const float p[3], const char *str, float size, float thickness,
               ms_rgba8 col)
{
    ms_dl_texts *s = &dl->texts;
    size_t len = strlen(str) + 1;
    if (s->nchars > UINT32_MAX - len) return -1;
    if (ms_grow((void **)&s->chars, &s->ccap, s->nchars + len, 1)) return -1;
    long i = one_more(dl, MS_DL_TEXTS);
    if (i < 0) return -1;
    copy3(s->xyz + 3 * i, p);
    s->size[i] = size;
    s->thickness[i] = thickness;
    s->color[i] = col;
    s->start[i] = (uint32_t)s->nchars;
    memcpy(s->chars + s->nchars, str, len);
    s->nchars += len;
    return 0;
}

long ms_dl_vertex(ms_displaylist *dl, const float p[3], const float n[3], ms_rgba8 col)
{
    ms_dl_mesh *m = &dl->mesh;
    if (m->nverts == m->vcap && mesh_grow(m, 1, 0)) return -1;
    size_t i = m->nverts++;
    copy3(m->xyz + 3 * i, p);
    for (int k = 0; k < 3; k++) m->normal[3 * i + k] = ms_normal_quantize(n[k]);
    m->color[i] = col;
    return (long)i;
}

int ms_dl_tri(ms_displaylist *dl, uint32_t i, uint32_t j, uint32_t k)
{
    ms_dl_mesh *m = &dl->mesh;
    if (m->ntris == m->tcap && mesh_grow(m, 0, 1)) return -1;
    uint32_t *t = m->tri + 3 * m->ntris++;
    t[0] = i;
    t[1] = j;
    t[2] = k;
    return 0;
}

int ms_dl_triangle(ms_displaylist *dl, const float p[9], const float n[9], const ms_rgba8 c[3])
{
    if (mesh_grow(&dl->mesh, 3, 1)) return -1;
    uint32_t v = (uint32_t)dl->mesh.nverts;
    for (int k = 0; k < 3; k++) ms_dl_vertex(dl, p + 3 * k, n + 3 * k, c[k]);
    return ms_dl_tri(dl, v, v + 1, v + 2);
}

size_t ms_dl_count(const ms_displaylist *dl)
{
    return dl->spheres.n + dl->cylinders.n + dl->cones.n + dl->lines.n + dl->points.n +
           dl->texts.n + dl->mesh.ntris;
}

size_t ms_dl_bytes(const ms_displaylist *dl)
{
    return dl->spheres.cap * (4 * sizeof(float) + sizeof(ms_rgba8) + 2) +
           dl->cylinders.cap * (10 * sizeof(float) + 2 * sizeof(ms_rgba8) + 3) +
           dl->cylinders.ordercap * sizeof(uint32_t) +
           dl->cones.cap * (8 * sizeof(float) + sizeof(ms_rgba8) + 2) +
           dl->lines.cap * (7 * sizeof(float) + sizeof(ms_rgba8) + 1) +
           dl->points.cap * (4 * sizeof(float) + sizeof(ms_rgba8)) +
           dl->texts.cap * (5 * sizeof(float) + sizeof(ms_rgba8) + 4) + dl->texts.ccap +
           dl->mesh.vcap * (3 * sizeof(float) + 3 + sizeof(ms_rgba8)) +
           dl->mesh.tcap * 3 * sizeof(uint32_t);
}

static void extend_box(const float *p, size_t n, float lo[3], float hi[3], int *any)
{
    for (size_t i = 0; i < n; i++, p += 3) {
        if (!*any) {
            copy3(lo, p);
            copy3(hi, p);
            *any = 1;
            continue;
        }
        for (int k = 0; k < 3; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
    }
}

int ms_dl_bounds(const ms_displaylist *dl, float lo[3], float hi[3])
{
    int any = 0;
    extend_box(dl->spheres.xyz, dl->spheres.n, lo, hi, &any);
    extend_box(dl->cylinders.base, dl->cylinders.n, lo, hi, &any);
    extend_box(dl->cylinders.apex, dl->cylinders.n, lo, hi, &any);
    extend_box(dl->cones.base, dl->cones.n, lo, hi, &any);
    extend_box(dl->cones.apex, dl->cones.n, lo, hi, &any);
    extend_box(dl->lines.a, dl->lines.n, lo, hi, &any);
    extend_box(dl->lines.b, dl->lines.n, lo, hi, &any);
    extend_box(dl->points.xyz, dl->points.n, lo, hi, &any);
    extend_box(dl->texts.xyz, dl->texts.n, lo, hi, &any);
    extend_box(dl->mesh.xyz, dl->mesh.nverts, lo, hi, &any);
    return any;
}

ms_rgba8 ms_rgba8_from_float(const float rgb[3], float alpha)
{
    float v[4] = {rgb[0], rgb[1], rgb[2], alpha};
    uint8_t o[4];
    for (int k = 0; k < 4; k++) {
        float x = v[k] < 0 ? 0 : v[k] > 1 ? 1 : v[k];
        o[k] = (uint8_t)(x * 255.0f + 0.5f);
    }
    return (ms_rgba8){o[0], o[1], o[2], o[3]};
}
