/* ring.c: rings and discs (Tachyon's Ring: the part of a plane between an inner and an outer
 * radius around a centre), an Embree user geometry. The closed ends of cylinders and the
 * bases of cones are discs (inner radius 0). */
#include "config.h"
#include "rt/rt_internal.h"

#include <math.h>

static void ring_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    size_t i = args->primID;
    const float *c = g->a + 3 * i, *nr = g->b + 3 * i;
    float r = g->ra[i], n2 = ms_v3f_dot(nr, nr);
    struct RTCBounds *o = args->bounds_o;
    if (!(r > 0) || !(n2 > 0) || !isfinite(n2) || !isfinite(r) ||
        !isfinite(c[0] + c[1] + c[2])) {
        rt_bounds_empty(o);
        return;
    }
    float e[3];
    for (int k = 0; k < 3; k++) e[k] = r * sqrtf(fmaxf(0.0f, 1.0f - nr[k] * nr[k] / n2));
    o->lower_x = c[0] - e[0], o->upper_x = c[0] + e[0];
    o->lower_y = c[1] - e[1], o->upper_y = c[1] + e[1];
    o->lower_z = c[2] - e[2], o->upper_z = c[2] + e[2];
}

static int ring_test(const rt_geom *g, unsigned prim, const rt_uray *r, float t[2])
{
    const float *c = g->a + 3 * (size_t)prim;
    float n[3] = {g->b[3 * (size_t)prim], g->b[3 * (size_t)prim + 1], g->b[3 * (size_t)prim + 2]};
    ms_v3f_normalize_rcp(n);
    float den = ms_v3f_dot(r->d, n);
    if (den == 0.0f) return 0;
    float co[3] = {c[0] - r->o[0], c[1] - r->o[1], c[2] - r->o[2]};
    float tt = ms_v3f_dot(co, n) / den;
    if (!(tt > r->tnear && tt < r->tfar)) return 0;
    float q[3] = {tt * r->d[0] - co[0], tt * r->d[1] - co[1], tt * r->d[2] - co[2]};
    float d2 = ms_v3f_dot(q, q), ro = g->ra[prim], ri = g->rb[prim];
    if (d2 > ro * ro || d2 < ri * ri) return 0;
    t[0] = tt;
    return 1;
}

static void ring_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    rt_user_intersect(args, ring_test);
}

static void ring_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    rt_user_occluded(args, ring_test);
}

static RTCGeometry ring_geometry(rt_world *w, rt_geom *g, ms_error *err)
{
    return rt_user_geometry(w, g, ring_bounds, ring_intersect, ring_occluded, err);
}

static void ring_surface(const rt_geom *g, const struct RTCHit *h, const float p[3], float n[3],
                         float ng[3], ms_rgba8 *c)
{
    for (int k = 0; k < 3; k++) n[k] = ng[k] = g->b[3 * (size_t)h->primID + k];
    *c = g->color[h->primID];
}

const rt_prim rt_ring_prim = {"rings", ring_geometry, ring_surface};
