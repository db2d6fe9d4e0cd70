/* cylinder.c: open cylinders (Tachyon's FCylinder), an Embree user geometry: the tube between
 * the base and apex centres, both of its surfaces (a ray can see the inside of an open end).
 * Closed ends are discs (ring.c). The test first moves the ray origin next to the cylinder,
 * so that a camera far away in the list's coordinates loses no precision. */
#include "config.h"
#include "rt/rt_internal.h"

#include <math.h>

static void cylinder_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    size_t i = args->primID;
    const float *a = g->a + 3 * i, *b = g->b + 3 * i;
    float r = g->ra[i], w[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float len2 = rt_dot(w, w);
    struct RTCBounds *o = args->bounds_o;
    if (!(r > 0) || !(len2 > 0) || !isfinite(len2) || !isfinite(r)) {
        rt_bounds_empty(o);
        return;
    }
    float e[3];
    for (int k = 0; k < 3; k++) e[k] = r * sqrtf(fmaxf(0.0f, 1.0f - w[k] * w[k] / len2));
    o->lower_x = fminf(a[0], b[0]) - e[0], o->upper_x = fmaxf(a[0], b[0]) + e[0];
    o->lower_y = fminf(a[1], b[1]) - e[1], o->upper_y = fmaxf(a[1], b[1]) + e[1];
    o->lower_z = fminf(a[2], b[2]) - e[2], o->upper_z = fmaxf(a[2], b[2]) + e[2];
}

static int cylinder_test(const rt_geom *g, unsigned prim, const rt_uray *r, float t[2])
{
    const float *A = g->a + 3 * (size_t)prim, *B = g->b + 3 * (size_t)prim;
    float rad = g->ra[prim], ax[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    float len = rt_normalize(ax);
    /* the origin moved to the point of the ray nearest the cylinder's middle */
    float mid[3] = {0.5f * (A[0] + B[0]) - r->o[0], 0.5f * (A[1] + B[1]) - r->o[1],
                    0.5f * (A[2] + B[2]) - r->o[2]};
    float t0 = rt_dot(mid, r->d) / rt_dot(r->d, r->d);
    float oc[3], dp[3], ocp[3];
    for (int k = 0; k < 3; k++) oc[k] = r->o[k] + t0 * r->d[k] - A[k];
    float ds = rt_dot(r->d, ax), ocs = rt_dot(oc, ax);
    for (int k = 0; k < 3; k++) {
        dp[k] = r->d[k] - ds * ax[k];
        ocp[k] = oc[k] - ocs * ax[k];
    }
    float qa = rt_dot(dp, dp), roots[2];
    if (!(qa > 0.0f) ||
        !rt_quadratic(qa, rt_dot(dp, ocp), rt_dot(ocp, ocp) - rad * rad, &roots[0], &roots[1]))
        return 0;
    int n = 0;
    for (int k = 0; k < 2; k++) {
        float tt = t0 + roots[k], s = ocs + roots[k] * ds;
        if (tt > r->tnear && tt < r->tfar && s >= 0.0f && s <= len) t[n++] = tt;
    }
    return n;
}

static void cylinder_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    rt_user_intersect(args, cylinder_test);
}

static void cylinder_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    rt_user_occluded(args, cylinder_test);
}

static RTCGeometry cylinder_geometry(rt_world *w, const rt_geom *g, ms_error *err)
{
    return rt_user_geometry(w, g, cylinder_bounds, cylinder_intersect, cylinder_occluded, err);
}

/* The radial direction at the hit. */
static void cylinder_surface(const rt_geom *g, const struct RTCHit *h, const float p[3], float n[3],
                             float ng[3], ms_rgba8 *c)
{
    const float *A = g->a + 3 * (size_t)h->primID, *B = g->b + 3 * (size_t)h->primID;
    float ax[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, q[3] = {p[0] - A[0], p[1] - A[1], p[2] - A[2]};
    rt_normalize(ax);
    float s = rt_dot(q, ax);
    for (int k = 0; k < 3; k++) n[k] = ng[k] = q[k] - s * ax[k];
    *c = g->color[h->primID];
}

const rt_prim rt_cylinder_prim = {"cylinders", cylinder_geometry, cylinder_surface};
