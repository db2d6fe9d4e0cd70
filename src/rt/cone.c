/* cone.c: cones, truncated or pointed (radius rbase at the base, rapex at the apex), an
 * Embree user geometry: the exact slanted surface between the two ends, both of its sides.
 * The base disc is a ring (ring.c), as the Tachyon exporter closes cone bases. */
#include "config.h"
#include "rt/rt_internal.h"

#include <math.h>

static void cone_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    size_t i = args->primID;
    const float *a = g->a + 3 * i, *b = g->b + 3 * i;
    float ra = g->ra[i], rb = g->rb[i], w[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float len2 = ms_v3f_dot(w, w);
    struct RTCBounds *o = args->bounds_o;
    if (!(ra >= 0) || !(rb >= 0) || !(ra + rb > 0) || !(len2 > 0) || !isfinite(len2) ||
        !isfinite(ra + rb)) {
        rt_bounds_empty(o);
        return;
    }
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        float s = sqrtf(fmaxf(0.0f, 1.0f - w[k] * w[k] / len2));
        lo[k] = fminf(a[k] - ra * s, b[k] - rb * s);
        hi[k] = fmaxf(a[k] + ra * s, b[k] + rb * s);
    }
    o->lower_x = lo[0], o->lower_y = lo[1], o->lower_z = lo[2];
    o->upper_x = hi[0], o->upper_y = hi[1], o->upper_z = hi[2];
}

/* |p_perp|^2 = (ra + k s)^2 along the ray, from an origin moved next to the cone. */
static int cone_test(const rt_geom *g, unsigned prim, const rt_uray *r, float t[2])
{
    const float *A = g->a + 3 * (size_t)prim, *B = g->b + 3 * (size_t)prim;
    float ra = g->ra[prim], ax[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    float len = ms_v3f_normalize_rcp(ax), k = (g->rb[prim] - ra) / len;
    float mid[3] = {0.5f * (A[0] + B[0]) - r->o[0], 0.5f * (A[1] + B[1]) - r->o[1],
                    0.5f * (A[2] + B[2]) - r->o[2]};
    float t0 = ms_v3f_dot(mid, r->d) / ms_v3f_dot(r->d, r->d), oc[3];
    for (int j = 0; j < 3; j++) oc[j] = r->o[j] + t0 * r->d[j] - A[j];
    float ds = ms_v3f_dot(r->d, ax), ocs = ms_v3f_dot(oc, ax), r0 = ra + k * ocs;
    float qa = ms_v3f_dot(r->d, r->d) - ds * ds - k * k * ds * ds;
    float qb = ms_v3f_dot(oc, r->d) - ocs * ds - k * ds * r0;
    float qc = ms_v3f_dot(oc, oc) - ocs * ocs - r0 * r0, roots[2];
    if (fabsf(qa) < 1e-12f * ms_v3f_dot(r->d, r->d)) {
        if (qb == 0.0f) return 0;
        roots[0] = -0.5f * qc / qb;
        roots[1] = INFINITY;
    } else if (!rt_quadratic(qa, qb, qc, &roots[0], &roots[1])) {
        return 0;
    }
    int n = 0;
    for (int j = 0; j < 2; j++) {
        float tt = t0 + roots[j], s = ocs + roots[j] * ds;
        if (tt > r->tnear && tt < r->tfar && s >= 0.0f && s <= len && ra + k * s >= 0.0f) t[n++] = tt;
    }
    return n;
}

static void cone_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    rt_user_intersect(args, cone_test);
}

static void cone_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    rt_user_occluded(args, cone_test);
}

static RTCGeometry cone_geometry(rt_world *w, rt_geom *g, ms_error *err)
{
    return rt_user_geometry(w, g, cone_bounds, cone_intersect, cone_occluded, err);
}

/* The gradient of |p_perp| - (ra + k s): the radial direction tilted by the slope. */
static void cone_surface(const rt_geom *g, const struct RTCHit *h, const float p[3], float n[3],
                         float ng[3], ms_rgba8 *c)
{
    size_t i = h->primID;
    const float *A = g->a + 3 * i, *B = g->b + 3 * i;
    float ax[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, q[3] = {p[0] - A[0], p[1] - A[1], p[2] - A[2]};
    float len = ms_v3f_normalize_rcp(ax), k = (g->rb[i] - g->ra[i]) / len, s = ms_v3f_dot(q, ax), perp[3];
    for (int j = 0; j < 3; j++) perp[j] = q[j] - s * ax[j];
    ms_v3f_normalize_rcp(perp);
    for (int j = 0; j < 3; j++) n[j] = ng[j] = perp[j] - k * ax[j];
    *c = g->color[i];
}

const rt_prim rt_cone_prim = {"cones", cone_geometry, cone_surface};
