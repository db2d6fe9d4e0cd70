/* mesh.c: a display list's triangle mesh, an Embree triangle geometry that shares the list's
 * own float vertices and 32-bit indices (no copy; the list keeps a spare vertex at the end
 * because Embree reads 16 bytes per vertex). Normals (signed bytes) and colours (RGBA8) are
 * read from the list and interpolated at each hit. Indices are checked first: a triangle
 * naming a vertex that does not exist is an error, not a wild read. */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/threads.h"

#include <stdatomic.h>
#include <string.h>

typedef struct check {
    const rt_geom *g;
    atomic_size_t bad;          /* first bad triangle + 1 (0: none) */
} check;

static void check_range(void *ctx, size_t b, size_t e, int thread)
{
    check *c = ctx;
    const uint32_t *t = c->g->tri;
    for (size_t i = b; i < e; i++)
        if (t[3 * i] >= c->g->nverts || t[3 * i + 1] >= c->g->nverts || t[3 * i + 2] >= c->g->nverts) {
            atomic_store(&c->bad, i + 1);
            return;
        }
}

static RTCGeometry mesh_geometry(rt_world *w, rt_geom *g, ms_error *err)
{
    check c = {g, 0};
    ms_parallel_for(g->n, 65536, check_range, &c);
    size_t bad = atomic_load(&c.bad);
    if (bad) {
        ms_error_set(err, "mesh: triangle %zu names a vertex beyond the %zu vertices", bad - 1,
                     g->nverts);
        return NULL;
    }
    if (g->n > 0xffffffffu || g->nverts > 0xffffffffu) {
        ms_error_set(err, "mesh: more than 2^32 triangles or vertices");
        return NULL;
    }
    const float *xyz = g->xyz;
    if (g->vcap <= g->nverts) {     /* a list made without the spare vertex: pad a copy */
        float *copy = rt_world_alloc(w, 3 * g->nverts + 4, sizeof(float), err);
        if (!copy) return NULL;
        memcpy(copy, g->xyz, 3 * g->nverts * sizeof(float));
        xyz = copy;
    }
    RTCGeometry geom = rtcNewGeometry(w->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geom) {
        if (!rt_device_check(w->dev, "mesh", err)) ms_error_set(err, "mesh: out of memory");
        return NULL;
    }
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, xyz, 0,
                               3 * sizeof(float), g->nverts);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, g->tri, 0,
                               3 * sizeof(uint32_t), g->n);
    return geom;
}

static uint8_t mix8(uint8_t a, uint8_t b, uint8_t c, float wa, float wb, float wc)
{
    float v = wa * a + wb * b + wc * c + 0.5f;
    return (uint8_t)(v < 0.0f ? 0.0f : v > 255.0f ? 255.0f : v);
}

/* Interpolated vertex normal and colour; Embree's geometric normal (in the list's
 * coordinates, under the instance); both turned to world space by the normal matrix. */
static void mesh_surface(const rt_geom *g, const struct RTCHit *h, const float p[3], float n[3],
                         float ng[3], ms_rgba8 *c)
{
    const uint32_t *t = g->tri + 3 * (size_t)h->primID;
    float wb = h->u, wc = h->v, wa = 1.0f - wb - wc, nl[3], gl[3] = {h->Ng_x, h->Ng_y, h->Ng_z};
    const int8_t *na = g->normal + 3 * (size_t)t[0], *nb = g->normal + 3 * (size_t)t[1],
                 *nc = g->normal + 3 * (size_t)t[2];
    for (int k = 0; k < 3; k++)
        nl[k] = wa * ms_normal_dequantize(na[k]) + wb * ms_normal_dequantize(nb[k]) +
                wc * ms_normal_dequantize(nc[k]);
    rt_m3_vec(g->nm, nl, n);
    rt_m3_vec(g->nm, gl, ng);
    ms_rgba8 ca = g->color[t[0]], cb = g->color[t[1]], cc = g->color[t[2]];
    c->r = mix8(ca.r, cb.r, cc.r, wa, wb, wc);
    c->g = mix8(ca.g, cb.g, cc.g, wa, wb, wc);
    c->b = mix8(ca.b, cb.b, cc.b, wa, wb, wc);
    c->a = mix8(ca.a, cb.a, cc.a, wa, wb, wc);
}

const rt_prim rt_mesh_prim = {"mesh", mesh_geometry, mesh_surface};
