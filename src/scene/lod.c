/* lod.c: vertex-clustering decimation of triangle meshes on a uniform grid (lod.h) and the
 * cache of a scene's decimated lists that the live view draws while the page drags. */
#include "config.h"
#include "scene/lod.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DIM 1048576.0          /* cubes along one axis at most (keys fit 60 bits) */
#define MS_LOD_SMALL 4096          /* a mesh of this many triangles or fewer is kept whole */

static int oom(ms_error *err)
{
    ms_error_set(err, "out of memory for the level of detail");
    return -1;
}

void ms_mesh_free(ms_dl_mesh *m)
{
    free(m->xyz);
    free(m->normal);
    free(m->color);
    free(m->tri);
    memset(m, 0, sizeof *m);
}

/* ---------------------------------------------------------------- the grid */

/* Cube keys to output vertices: open addressing, a power of two at least twice the keys. */
typedef struct cell_map {
    uint64_t *key;                 /* key + 1; 0 = empty */
    uint32_t *id;
    size_t mask, n;
} cell_map;

static int map_init(cell_map *m, size_t nkeys)
{
    size_t size = 16;
    while (size < 2 * nkeys) size *= 2;
    m->key = calloc(size, sizeof *m->key);
    m->id = malloc(size * sizeof *m->id);
    m->mask = size - 1;
    m->n = 0;
    return m->key && m->id ? 0 : -1;
}

static uint32_t map_find(cell_map *m, uint64_t key)
{
    size_t h = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 20) & m->mask;
    while (m->key[h] && m->key[h] != key + 1) h = (h + 1) & m->mask;
    if (!m->key[h]) {
        m->key[h] = key + 1;
        m->id[h] = (uint32_t)m->n++;
    }
    return m->id[h];
}

/* Sums over the vertices of each occupied cube. */
typedef struct sums {
    double *xyz;
    float *normal;
    uint32_t *rgba, *count;
} sums;

static void sums_free(sums *s)
{
    free(s->xyz);
    free(s->normal);
    free(s->rgba);
    free(s->count);
}

static int sums_init(sums *s, size_t n)
{
    s->xyz = calloc(3 * n, sizeof *s->xyz);
    s->normal = calloc(3 * n, sizeof *s->normal);
    s->rgba = calloc(4 * n, sizeof *s->rgba);
    s->count = calloc(n, sizeof *s->count);
    return s->xyz && s->normal && s->rgba && s->count ? 0 : -1;
}

static void bounds(const ms_dl_mesh *m, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = m->xyz[k];
    for (size_t v = 1; v < m->nverts; v++)
        for (int k = 0; k < 3; k++) {
            float x = m->xyz[3 * v + k];
            lo[k] = x < lo[k] ? x : lo[k];
            hi[k] = x > hi[k] ? x : hi[k];
        }
}

/* Each vertex's cube (remap[v] = its output vertex) and the sums of the cubes. */
static void cluster_vertices(const ms_dl_mesh *in, float cell, cell_map *map, sums *s,
                             uint32_t *remap)
{
    float lo[3], hi[3];
    bounds(in, lo, hi);
    double dim[3];
    for (int k = 0; k < 3; k++) dim[k] = floor((hi[k] - lo[k]) / cell) + 1.0;
    for (size_t v = 0; v < in->nverts; v++) {
        const float *p = in->xyz + 3 * v;
        uint64_t c[3];
        for (int k = 0; k < 3; k++) {
            double i = floor((p[k] - lo[k]) / cell);
            c[k] = (uint64_t)(i < 0 ? 0 : i >= dim[k] ? dim[k] - 1 : i);
        }
        uint32_t id = map_find(map, c[0] + (uint64_t)dim[0] * (c[1] + (uint64_t)dim[1] * c[2]));
        remap[v] = id;
        for (int k = 0; k < 3; k++) {
            s->xyz[3 * id + k] += p[k];
            s->normal[3 * id + k] += ms_normal_dequantize(in->normal[3 * v + k]);
        }
        const ms_rgba8 col = in->color[v];
        s->rgba[4 * id] += col.r;
        s->rgba[4 * id + 1] += col.g;
        s->rgba[4 * id + 2] += col.b;
        s->rgba[4 * id + 3] += col.a;
        s->count[id]++;
    }
}

/* The means of the cubes as the output's vertices. */
static void mean_vertices(const sums *s, size_t n, ms_dl_mesh *out)
{
    for (size_t i = 0; i < n; i++) {
        uint32_t c = s->count[i];
        float nrm[3], len = 0.0f;
        for (int k = 0; k < 3; k++) {
            out->xyz[3 * i + k] = (float)(s->xyz[3 * i + k] / c);
            nrm[k] = s->normal[3 * i + k];
            len += nrm[k] * nrm[k];
        }
        len = len > 0.0f ? sqrtf(len) : 1.0f;
        for (int k = 0; k < 3; k++) out->normal[3 * i + k] = ms_normal_quantize(nrm[k] / len);
        uint32_t h = c / 2;
        out->color[i] = (ms_rgba8){(uint8_t)((s->rgba[4 * i] + h) / c),
                                   (uint8_t)((s->rgba[4 * i + 1] + h) / c),
                                   (uint8_t)((s->rgba[4 * i + 2] + h) / c),
                                   (uint8_t)((s->rgba[4 * i + 3] + h) / c)};
    }
}

/* The triangles whose three corners fall in three different cubes. */
static void map_triangles(const ms_dl_mesh *in, const uint32_t *remap, ms_dl_mesh *out)
{
    size_t n = 0;
    for (size_t t = 0; t < in->ntris; t++) {
        const uint32_t *v = in->tri + 3 * t;
        if (v[0] >= in->nverts || v[1] >= in->nverts || v[2] >= in->nverts) continue;
        uint32_t a = remap[v[0]], b = remap[v[1]], c = remap[v[2]];
        if (a == b || b == c || a == c) continue;
        out->tri[3 * n] = a;
        out->tri[3 * n + 1] = b;
        out->tri[3 * n + 2] = c;
        n++;
    }
    out->ntris = n;
}

static int alloc_out(ms_dl_mesh *out, size_t nverts, size_t ntris)
{
    memset(out, 0, sizeof *out);
    out->vcap = nverts + 1;        /* one vertex more than used, as every mesh */
    out->tcap = ntris;
    out->xyz = malloc(3 * out->vcap * sizeof *out->xyz);
    out->normal = malloc(3 * out->vcap * sizeof *out->normal);
    out->color = malloc(out->vcap * sizeof *out->color);
    out->tri = malloc((ntris ? 3 * ntris : 1) * sizeof *out->tri);
    return out->xyz && out->normal && out->color && out->tri ? 0 : -1;
}

int ms_mesh_cluster(const ms_dl_mesh *in, float cell, ms_dl_mesh *out, ms_error *err)
{
    memset(out, 0, sizeof *out);
    if (!(cell > 0.0f) || !isfinite(cell)) {
        ms_error_set(err, "level of detail: the cell size %g is not a positive number", cell);
        return -1;
    }
    if (in->nverts == 0) return alloc_out(out, 0, 0) ? (ms_mesh_free(out), oom(err)) : 0;
    float lo[3], hi[3];
    bounds(in, lo, hi);
    for (int k = 0; k < 3; k++)      /* keys stay within 60 bits */
        if ((hi[k] - lo[k]) / cell >= MAX_DIM) cell = (float)((hi[k] - lo[k]) / (MAX_DIM - 1));
    cell_map map = {0};
    sums s = {0};
    uint32_t *remap = malloc(in->nverts * sizeof *remap);
    int rc = -1;
    if (remap && map_init(&map, in->nverts) == 0 && sums_init(&s, in->nverts) == 0) {
        cluster_vertices(in, cell, &map, &s, remap);
        if (alloc_out(out, map.n, in->ntris) == 0) {
            out->nverts = map.n;
            mean_vertices(&s, map.n, out);
            map_triangles(in, remap, out);
            rc = 0;
        }
    }
    free(remap);
    free(map.key);
    free(map.id);
    sums_free(&s);
    if (rc) {
        ms_mesh_free(out);
        return oom(err);
    }
    return 0;
}

/* ---------------------------------------------------------------- to a triangle count */

static double mesh_area(const ms_dl_mesh *m)
{
    double a = 0.0;
    for (size_t t = 0; t < m->ntris; t++) {
        const uint32_t *v = m->tri + 3 * t;
        if (v[0] >= m->nverts || v[1] >= m->nverts || v[2] >= m->nverts) continue;
        const float *p = m->xyz + 3 * v[0], *q = m->xyz + 3 * v[1], *r = m->xyz + 3 * v[2];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = q[k] - p[k];
            e2[k] = r[k] - p[k];
        }
        double c0 = e1[1] * e2[2] - e1[2] * e2[1], c1 = e1[2] * e2[0] - e1[0] * e2[2],
               c2 = e1[0] * e2[1] - e1[1] * e2[0];
        a += 0.5 * sqrt(c0 * c0 + c1 * c1 + c2 * c2);
    }
    return a;
}

int ms_mesh_decimate(const ms_dl_mesh *in, size_t max_tris, ms_dl_mesh *out, float *cell_used,
                     ms_error *err)
{
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    if (in->nverts) bounds(in, lo, hi);
    double extent = MS_MAX(MS_MAX(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
    /* a surface of area A in cubes of side h keeps about 1.5 A / h^2 vertices and twice as
     * many triangles */
    double cell = max_tris ? sqrt(3.0 * mesh_area(in) / (double)max_tris) : 0.0;
    if (!(cell > 0.0)) cell = extent > 0.0 ? extent / 64.0 : 1.0;
    for (int tries = 0;; tries++) {
        if (tries == 30 || cell > 2.0 * extent) cell = 2.0 * extent + 1.0;   /* one cube */
        if (ms_mesh_cluster(in, (float)cell, out, err)) return -1;
        if (out->ntris <= max_tris) break;
        double grow = 1.05 * sqrt((double)out->ntris / (double)MS_MAX(max_tris, 1));
        cell *= grow > 1.1 ? grow : 1.1;
        ms_mesh_free(out);
    }
    if (cell_used) *cell_used = (float)cell;
    return 0;
}

/* ---------------------------------------------------------------- the scene's cache */

struct ms_lod_entry {
    const ms_displaylist *src;     /* the list decimated, and its state then */
    unsigned long gen;
    size_t nverts, ntris, budget;
    ms_dl_mesh mesh;               /* the decimated mesh */
    ms_displaylist view;           /* the source's other primitives (shared) with mesh */
    int used;
};

void ms_scene_lod_init(ms_scene_lod *l) { memset(l, 0, sizeof *l); }

static void entry_free(ms_lod_entry *e)
{
    ms_mesh_free(&e->mesh);
    free(e);
}

void ms_scene_lod_free(ms_scene_lod *l)
{
    for (size_t i = 0; i < l->n; i++) entry_free(l->e[i]);
    free(l->e);
    memset(l, 0, sizeof *l);
}

size_t ms_scene_triangles(const ms_scene *s)
{
    size_t n = 0;
    for (size_t i = 0; i < s->nitems; i++) n += s->items[i].dl->mesh.ntris;
    return n;
}

static ms_lod_entry *find_entry(ms_scene_lod *l, const ms_displaylist *dl)
{
    for (size_t i = 0; i < l->n; i++)
        if (l->e[i]->src == dl) return l->e[i];
    return NULL;
}

/* The entry of dl decimated to budget, made or remade when dl changed. */
static ms_lod_entry *entry_for(ms_scene_lod *l, const ms_displaylist *dl, size_t budget,
                               ms_error *err)
{
    ms_lod_entry *e = find_entry(l, dl);
    if (e && e->gen == dl->gen && e->nverts == dl->mesh.nverts && e->ntris == dl->mesh.ntris &&
        e->budget == budget)
        return e;
    if (!e) {
        if (ms_grow((void **)&l->e, &l->cap, l->n + 1, sizeof *l->e) ||
            !(e = calloc(1, sizeof *e))) {
            oom(err);
            return NULL;
        }
        l->e[l->n++] = e;
    }
    ms_mesh_free(&e->mesh);
    e->src = NULL;                 /* until it is made again */
    if (ms_mesh_decimate(&dl->mesh, budget, &e->mesh, NULL, err)) return NULL;
    *e = (ms_lod_entry){dl, dl->gen, dl->mesh.nverts, dl->mesh.ntris, budget, e->mesh,
                        e->view, 0};
    return e;
}

/* Free the entries not used by this scene. */
static void prune(ms_scene_lod *l)
{
    size_t k = 0;
    for (size_t i = 0; i < l->n; i++) {
        if (l->e[i]->used) l->e[k++] = l->e[i];
        else entry_free(l->e[i]);
    }
    l->n = k;
}

int ms_scene_lod_apply(ms_scene_lod *l, ms_scene *s, size_t max_tris, size_t *tris,
                       ms_error *err)
{
    size_t total = ms_scene_triangles(s);
    *tris = total;
    for (size_t i = 0; i < l->n; i++) l->e[i]->used = 0;
    if (total <= max_tris) {
        prune(l);
        return 0;
    }
    /* small meshes (axes, a ligand's surface) stay whole when they leave most of the budget */
    size_t small = 0;
    for (size_t i = 0; i < s->nitems; i++)
        if (s->items[i].dl->mesh.ntris <= MS_LOD_SMALL) small += s->items[i].dl->mesh.ntris;
    size_t keep = small <= max_tris / 2 ? MS_LOD_SMALL : 0;
    if (!keep) small = 0;
    const ms_displaylist **lists = malloc((s->nitems ? s->nitems : 1) * sizeof *lists);
    if (!lists) return oom(err);
    for (size_t i = 0; i < s->nitems; i++) {
        const ms_displaylist *dl = s->items[i].dl;
        size_t budget = (size_t)((double)(max_tris - small) * (double)dl->mesh.ntris /
                                 (double)(total - small));
        int lighter = dl->mesh.ntris > keep;
        ms_lod_entry *e = lighter ? entry_for(l, dl, budget, err) : NULL;
        if (lighter && !e) {
            free(lists);
            return -1;
        }
        lists[i] = dl;
        if (!e) continue;
        e->used = 1;
        e->view = *dl;             /* today's other primitives, the decimated mesh */
        e->view.mesh = e->mesh;
        lists[i] = &e->view;
    }
    for (size_t i = 0; i < s->nitems; i++) s->items[i].dl = lists[i];
    free(lists);
    prune(l);
    *tris = ms_scene_triangles(s);
    return 0;
}
