/* raydump.c: the ray dump (MOLSCOPE_RT_RAYDUMP=file, off by default): every ray a
 * TachyonInternal render casts, by kind, with the scene's spheres (in world coordinates) and
 * meshes, so that a program of Embree alone (scripts/bench/rt_floor.c) can trace the same rays and give
 * the floor of the render. Each rendering thread appends its rays to its own buffer (one
 * test of a NULL pointer per ray when the dump is off); after each pass the calling thread
 * writes the buffers, thread by thread, through base/safewrite.h, so the file appears whole
 * or not at all. The layout (little-endian, doc/rt.md "Ray dump"):
 *
 *   header   "MSRAYS01", uint32 version (2), uint32 kinds (MS_RT_NRAYKINDS),
 *            uint64 spheres, uint64 other primitives (cylinders, cones, discs)
 *   spheres  float x, y, z, radius (world coordinates), 16 bytes each
 *   meshes   uint64 count; each: uint32 flags (RT_DUMP_MESH_*), float opacity, uint64
 *            vertices, uint64 triangles, float transform[12] (list to world, 3 x 4 row-major),
 *            then float x, y, z a vertex (the list's coordinates) and uint32 a, b, c a triangle
 *   rays     float org[3], tnear, dir[3], uint32 kind | mask << 8, 32 bytes each */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/safewrite.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(rt_rayrec) == 32, "a dumped ray is 32 bytes");

struct rt_raydump {
    ms_ofile *out;
    rt_raybuf *bufs;            /* per thread */
    int nbufs;
    int failed;                 /* a write failed or a buffer could not grow (err holds it) */
    ms_error err;
};

void rt_raybuf_add(rt_raybuf *b, int kind, unsigned mask, const float org[3], const float dir[3],
                   float tnear)
{
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 65536;
        rt_rayrec *r = b->oom ? NULL : realloc(b->r, cap * sizeof *r);
        if (!r) {
            b->oom = 1;
            return;
        }
        b->r = r, b->cap = cap;
    }
    rt_rayrec *r = &b->r[b->n++];
    memcpy(r->org, org, sizeof r->org);
    memcpy(r->dir, dir, sizeof r->dir);
    r->tnear = tnear;
    r->info = (uint32_t)kind | (mask & 0xffu) << 8;
}

/* A mesh's flags in the dump: how TachyonInternal built it, so that the floor builds it so. */
enum { RT_DUMP_MESH_TRANSPARENT = 1, RT_DUMP_MESH_MORTON = 2, RT_DUMP_MESH_COMPACT = 4 };

static void count_prims(const rt_world *w, uint64_t *spheres, uint64_t *meshes, uint64_t *other)
{
    *spheres = *meshes = *other = 0;
    for (size_t i = 0; i < w->ngeoms; i++) {
        if (w->geoms[i].kind == RT_SPHERE) *spheres += w->geoms[i].n;
        else if (w->geoms[i].kind == RT_MESH) (*meshes)++;
        else *other += w->geoms[i].n;
    }
}

/* The world's spheres (in world coordinates, place.c), in the order of its geometries. */
static int write_spheres(rt_raydump *d, const rt_world *w)
{
    for (size_t k = 0; k < w->ngeoms; k++) {
        const rt_geom *g = &w->geoms[k];
        for (size_t i = 0; g->kind == RT_SPHERE && i < g->n; i++) {
            float v[4] = {g->a[3 * i], g->a[3 * i + 1], g->a[3 * i + 2], g->ra[i]};
            if (ms_ofile_write(d->out, v, sizeof v, &d->err)) return -1;
        }
    }
    return 0;
}

/* The world's meshes (placed by their instances, see world.c), in the order of its
 * geometries. */
static int write_meshes(rt_raydump *d, const rt_world *w, uint64_t count)
{
    if (ms_ofile_write(d->out, &count, sizeof count, &d->err)) return -1;
    for (size_t k = 0; k < w->ngeoms; k++) {
        const rt_geom *g = &w->geoms[k];
        if (g->kind != RT_MESH) continue;
        unsigned char h[72];
        uint32_t flags = (g->transparent ? RT_DUMP_MESH_TRANSPARENT : 0) |
                         (g->morton ? RT_DUMP_MESH_MORTON : 0) | (g->compact ? RT_DUMP_MESH_COMPACT : 0);
        uint64_t n[2] = {g->nverts, g->n};
        memcpy(h, &flags, 4);
        memcpy(h + 4, &g->mat.opacity, 4);
        memcpy(h + 8, n, sizeof n);
        memcpy(h + 24, g->xf, 12 * sizeof(float));
        if (ms_ofile_write(d->out, h, sizeof h, &d->err) ||
            ms_ofile_write(d->out, g->xyz, 3 * g->nverts * sizeof(float), &d->err) ||
            ms_ofile_write(d->out, g->tri, 3 * g->n * sizeof(uint32_t), &d->err))
            return -1;
    }
    return 0;
}

static int write_header(rt_raydump *d, const rt_world *w, uint64_t *meshes)
{
    unsigned char h[32];
    uint32_t v[2] = {2, MS_RT_NRAYKINDS};
    uint64_t n[2];
    count_prims(w, &n[0], meshes, &n[1]);
    memcpy(h, "MSRAYS01", 8);
    memcpy(h + 8, v, sizeof v);
    memcpy(h + 16, n, sizeof n);
    return ms_ofile_write(d->out, h, sizeof h, &d->err);
}

rt_raydump *rt_raydump_open(const char *path, const rt_world *w, ms_error *err)
{
    rt_raydump *d = calloc(1, sizeof *d);
    if (d) d->nbufs = ms_threads_count();
    if (d) d->bufs = calloc((size_t)d->nbufs, sizeof *d->bufs);
    if (!d || !d->bufs) {
        free(d);
        ms_error_set(err, "MOLSCOPE_RT_RAYDUMP: out of memory");
        return NULL;
    }
    d->out = ms_ofile_open(path, &d->err);
    uint64_t meshes = 0;
    if (!d->out || write_header(d, w, &meshes) || write_spheres(d, w) || write_meshes(d, w, meshes)) {
        ms_error_set(err, "MOLSCOPE_RT_RAYDUMP: %s", d->err.msg);
        rt_raydump_close(d, 0, NULL);
        return NULL;
    }
    return d;
}

rt_raybuf *rt_raydump_buf(rt_raydump *d, int thread)
{
    return d ? &d->bufs[thread] : NULL;
}

void rt_raydump_flush(rt_raydump *d)
{
    for (int t = 0; d && t < d->nbufs; t++) {
        rt_raybuf *b = &d->bufs[t];
        if (b->oom && !d->failed) {
            ms_error_set(&d->err, "out of memory for the rays of a pass");
            d->failed = 1;
        }
        if (!d->failed && b->n && ms_ofile_write(d->out, b->r, b->n * sizeof *b->r, &d->err))
            d->failed = 1;
        b->n = 0;
    }
}

int rt_raydump_close(rt_raydump *d, int ok, ms_error *err)
{
    if (!d) return 0;
    int rc = 0;
    if (ok && d->failed) {
        ms_error_set(err, "MOLSCOPE_RT_RAYDUMP: %s", d->err.msg);
        rc = -1;
    }
    if (d->out && ms_ofile_finish(d->out, ok && !d->failed, &d->err) && rc == 0 && ok) {
        ms_error_set(err, "MOLSCOPE_RT_RAYDUMP: %s", d->err.msg);
        rc = -1;
    }
    for (int t = 0; t < d->nbufs; t++) free(d->bufs[t].r);
    free(d->bufs);
    free(d);
    return rc;
}
