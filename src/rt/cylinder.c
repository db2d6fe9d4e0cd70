/* cylinder.c: open cylinders (Tachyon's FCylinder), an Embree user geometry: the tube between
 * the base and apex centres, both of its surfaces (a ray can see the inside of an open end).
 * Closed ends are discs (ring.c). Each cylinder's unit axis and length are worked out once,
 * at the build, for the tests. */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/threads.h"

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

/* The ray against the infinite cylinder, in the plane across the axis (with the ray's part
 * across the axis dp and the origin's ocp): the point nearest the axis at tc, distance^2 l2,
 * the crossings tc -+ sqrt((r^2 - l2) / |dp|^2); then each within the two ends. Working from
 * the nearest point (as Embree's spheres do) keeps precision with a far camera. */
static int cylinder_test(const rt_geom *g, unsigned prim, const rt_uray *r, float t[2])
{
    const float *A = g->a + 3 * (size_t)prim, *ax = g->aux + 4 * (size_t)prim;
    float rad = g->ra[prim], oc[3] = {r->o[0] - A[0], r->o[1] - A[1], r->o[2] - A[2]};
    float ds = rt_dot(r->d, ax), ocs = rt_dot(oc, ax), dp[3], ocp[3];
    for (int k = 0; k < 3; k++) {
        dp[k] = r->d[k] - ds * ax[k];
        ocp[k] = oc[k] - ocs * ax[k];
    }
    float qa = rt_dot(dp, dp);
    if (!(qa > 0.0f)) return 0;          /* along the axis: an open tube is not hit */
    float inv = 1.0f / qa, tc = -rt_dot(ocp, dp) * inv, q[3];
    for (int k = 0; k < 3; k++) q[k] = ocp[k] + tc * dp[k];
    float l2 = rt_dot(q, q);
    if (l2 > rad * rad) return 0;
    float td = sqrtf((rad * rad - l2) * inv), roots[2] = {tc - td, tc + td};
    int n = 0;
    for (int k = 0; k < 2; k++) {
        float s = ocs + roots[k] * ds;
        if (roots[k] > r->tnear && roots[k] < r->tfar && s >= 0.0f && s <= ax[3]) t[n++] = roots[k];
    }
    return n;
}

/* Unit axes and lengths, 4 floats per cylinder, made once for the tests. */
typedef struct axes {
    const rt_geom *g;
    float *aux;
} axes;

static void axes_range(void *ctx, size_t b, size_t e, int thread)
{
    axes *x = ctx;
    for (size_t i = b; i < e; i++) {
        float *o = x->aux + 4 * i;
        for (int k = 0; k < 3; k++) o[k] = x->g->b[3 * i + k] - x->g->a[3 * i + k];
        o[3] = rt_normalize(o);
    }
}

static void cylinder_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    rt_user_intersect(args, cylinder_test);
}

static void cylinder_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    rt_user_occluded(args, cylinder_test);
}

static RTCGeometry cylinder_geometry(rt_world *w, rt_geom *g, ms_error *err)
{
    axes x = {g, rt_world_alloc(w, 4 * g->n, sizeof(float), err)};
    if (!x.aux) return NULL;
    ms_parallel_for(g->n, 65536, axes_range, &x);
    g->aux = x.aux;
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
