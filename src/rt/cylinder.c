/* cylinder.c: open cylinders (Tachyon's FCylinder), an Embree user geometry: the tube between
 * the base and apex centres, both of its surfaces (a ray can see the inside of an open end).
 * Closed ends are discs (ring.c). Each cylinder's unit axis and length, and the distance of
 * its joint along the axis, are worked out once, at the build, for the tests. A bond is one
 * cylinder whose colour changes at its joint (the display list's color2 beyond it): VMD's two
 * half cylinders with half the primitives to build and test. The spheres of the list centred
 * on a cylinder's ends (Licorice's atoms) are tested with it, as one primitive. */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void cylinder_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    size_t i = args->primID;
    const float *a = g->a + 3 * i, *b = g->b + 3 * i;
    float r = g->ra[i], w[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float len2 = ms_v3f_dot(w, w);
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
    float ds = ms_v3f_dot(r->d, ax), ocs = ms_v3f_dot(oc, ax), dp[3], ocp[3];
    for (int k = 0; k < 3; k++) {
        dp[k] = r->d[k] - ds * ax[k];
        ocp[k] = oc[k] - ocs * ax[k];
    }
    float qa = ms_v3f_dot(dp, dp);
    if (!(qa > 0.0f)) return 0;          /* along the axis: an open tube is not hit */
    float inv = 1.0f / qa, tc = -ms_v3f_dot(ocp, dp) * inv, q[3];
    for (int k = 0; k < 3; k++) q[k] = ocp[k] + tc * dp[k];
    float l2 = ms_v3f_dot(q, q);
    if (l2 > rad * rad) return 0;
    float td = sqrtf((rad * rad - l2) * inv), roots[2] = {tc - td, tc + td};
    int n = 0;
    for (int k = 0; k < 2; k++) {
        float s = ocs + roots[k] * ds;
        if (roots[k] > r->tnear && roots[k] < r->tfar && s >= 0.0f && s <= ax[3]) t[n++] = roots[k];
    }
    return n;
}

/* Unit axes and lengths, 4 floats per cylinder, and the joints' distances along the axes,
 * made once for the tests. */
typedef struct axes {
    const rt_geom *g;
    float *aux, *join;
} axes;

static void axes_range(void *ctx, size_t b, size_t e, int thread)
{
    axes *x = ctx;
    const rt_geom *g = x->g;
    for (size_t i = b; i < e; i++) {
        float *o = x->aux + 4 * i, d[3];
        for (int k = 0; k < 3; k++) {
            o[k] = g->b[3 * i + k] - g->a[3 * i + k];
            d[k] = g->joint[3 * i + k] - g->a[3 * i + k];
        }
        o[3] = ms_v3f_normalize_rcp(o);
        x->join[i] = sqrtf(ms_v3f_dot(d, d));
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

/* ---------------------------------------------------------------- spheres on the ends */

#define NO_SPHERE UINT32_MAX

static size_t point_slot(const float *p, size_t mask)
{
    uint32_t u[3];
    memcpy(u, p, sizeof u);
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int k = 0; k < 3; k++) {
        h = (h ^ u[k]) * 0xff51afd7ed558ccdull;
        h ^= h >> 32;
    }
    return (size_t)h & mask;
}

/* Whether cylinder i is a tube at all (a length and a radius): only then may it take spheres. */
static int tube_ok(const rt_geom *g, size_t i)
{
    const float *a = g->a + 3 * i, *b = g->b + 3 * i;
    float w[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, l2 = ms_v3f_dot(w, w);
    return g->ra[i] > 0.0f && isfinite(g->ra[i]) && l2 > 0.0f && isfinite(l2);
}

/* A sphere of the list centred exactly at p, not yet taken, that may join cylinder i (its
 * alpha the cylinder's, so the primitive has one opacity); UINT32_MAX when none. */
static uint32_t free_sphere(const rt_geom *g, const uint32_t *tab, size_t mask, const float *p,
                            size_t i)
{
    const ms_dl_spheres *sp = g->spheres;
    for (size_t s = point_slot(p, mask); tab[s] != NO_SPHERE; s = (s + 1) & mask) {
        uint32_t j = tab[s];
        if (!g->taken[j] && !memcmp(sp->xyz + 3 * (size_t)j, p, 3 * sizeof(float)) &&
            sp->color[j].a == g->color[i].a)
            return j;
    }
    return NO_SPHERE;
}

/* Give each cylinder the spheres of the list centred on its ends (Licorice's atoms), each
 * sphere to one cylinder: ends[] and endcol[], and taken[] for the sphere geometry to leave
 * them out. */
static int take_spheres(rt_world *w, rt_geom *g, ms_error *err)
{
    const ms_dl_spheres *sp = g->spheres;
    size_t cap = 1;
    while (cap < 2 * sp->n) cap *= 2;
    uint32_t *tab = malloc(cap * sizeof *tab);
    float *ends = rt_world_alloc(w, 8 * g->n, sizeof(float), err);
    ms_rgba8 *col = rt_world_alloc(w, 2 * g->n, sizeof(ms_rgba8), err);
    g->taken = rt_world_alloc(w, sp->n, 1, err);
    if (!tab || !ends || !col || !g->taken) {
        free(tab);
        if (!tab) ms_error_set(err, "cylinders: out of memory");
        return -1;
    }
    memset(tab, 0xff, cap * sizeof *tab);
    memset(g->taken, 0, sp->n);
    for (size_t j = 0; j < sp->n; j++) {
        if (!(sp->radius[j] > 0.0f)) continue;
        size_t s = point_slot(sp->xyz + 3 * j, cap - 1);
        while (tab[s] != NO_SPHERE) s = (s + 1) & (cap - 1);
        tab[s] = (uint32_t)j;
    }
    for (size_t i = 0; i < g->n; i++)
        for (int e = 0; e < 2; e++) {
            const float *p = (e ? g->b : g->a) + 3 * i;
            float *o = ends + 8 * i + 4 * e;
            uint32_t j = tube_ok(g, i) ? free_sphere(g, tab, cap - 1, p, i) : NO_SPHERE;
            memcpy(o, p, 3 * sizeof(float));
            o[3] = 0.0f;
            col[2 * i + e] = g->color[i];
            if (j == NO_SPHERE) continue;
            g->taken[j] = 1;
            o[3] = sp->radius[j];
            col[2 * i + e] = sp->color[j];
        }
    free(tab);
    g->ends = ends;
    g->endcol = col;
    return 0;
}

static void capsule_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    struct RTCBounds *o = args->bounds_o;
    cylinder_bounds(args);
    for (int e = 0; e < 2; e++) {
        const float *c = g->ends + 8 * (size_t)args->primID + 4 * e;
        float r = c[3];
        if (!(r > 0.0f) || !isfinite(r) || !isfinite(c[0] + c[1] + c[2])) continue;
        o->lower_x = fminf(o->lower_x, c[0] - r), o->upper_x = fmaxf(o->upper_x, c[0] + r);
        o->lower_y = fminf(o->lower_y, c[1] - r), o->upper_y = fmaxf(o->upper_y, c[1] + r);
        o->lower_z = fminf(o->lower_z, c[2] - r), o->upper_z = fmaxf(o->upper_z, c[2] + r);
    }
}

/* The crossings of the cylinder and of its end spheres: how many (in all[] when given), and
 * the nearest with its part (0 the tube, 1 the base sphere, 2 the far sphere). */
static int capsule_test(const rt_geom *g, unsigned prim, const rt_uray *r, float *near, int *part,
                        float all[6])
{
    float t[2];
    int n = cylinder_test(g, prim, r, t), total = n;
    *near = n ? t[0] : INFINITY;
    *part = 0;
    if (all) memcpy(all, t, (size_t)n * sizeof *t);
    for (int e = 0; e < 2; e++) {
        const float *c = g->ends + 8 * (size_t)prim + 4 * e;
        if (!(c[3] > 0.0f)) continue;
        n = rt_sphere_hits(c, c[3], r, t);
        if (all) memcpy(all + total, t, (size_t)n * sizeof *t);
        total += n;
        if (n && t[0] < *near) *near = t[0], *part = e + 1;
    }
    return total;
}

static void capsule_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    for (unsigned i = 0; i < args->N; i++) {
        rt_uray r;
        float t;
        int part;
        if (!args->valid[i]) continue;
        rt_user_ray((const float *)args->rayhit, args->N, i, &r);
        if (capsule_test(g, args->primID, &r, &t, &part, NULL)) rt_user_hit_part(args, i, t, (float)part);
    }
}

static void capsule_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    for (unsigned i = 0; i < args->N; i++) {
        rt_uray r;
        float t, all[6];
        int part;
        if (!args->valid[i]) continue;
        rt_user_ray((const float *)args->ray, args->N, i, &r);
        int n = capsule_test(g, args->primID, &r, &t, &part, all);
        if (n) rt_user_block(args, i, n, all, &r);
    }
}

static RTCGeometry cylinder_geometry(rt_world *w, rt_geom *g, ms_error *err)
{
    if (g->spheres && g->spheres->n && take_spheres(w, g, err)) return NULL;
    axes x = {g, rt_world_alloc(w, 4 * g->n, sizeof(float), err), rt_world_alloc(w, g->n, sizeof(float), err)};
    if (!x.aux || !x.join) return NULL;
    ms_parallel_for(g->n, 65536, axes_range, &x);
    g->aux = x.aux;
    g->join = x.join;
    if (g->ends) return rt_user_geometry(w, g, capsule_bounds, capsule_intersect, capsule_occluded, err);
    return rt_user_geometry(w, g, cylinder_bounds, cylinder_intersect, cylinder_occluded, err);
}

/* The radial direction at the hit. */
static void cylinder_surface(const rt_geom *g, const struct RTCHit *h, const float p[3], float n[3],
                             float ng[3], ms_rgba8 *c)
{
    if (g->ends && h->u > 0.0f) {         /* an end sphere */
        int e = h->u > 1.5f;
        const float *ctr = g->ends + 8 * (size_t)h->primID + 4 * e;
        for (int k = 0; k < 3; k++) n[k] = ng[k] = p[k] - ctr[k];
        *c = g->endcol[2 * (size_t)h->primID + (size_t)e];
        return;
    }
    const float *A = g->a + 3 * (size_t)h->primID, *B = g->b + 3 * (size_t)h->primID;
    float ax[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, q[3] = {p[0] - A[0], p[1] - A[1], p[2] - A[2]};
    ms_v3f_normalize_rcp(ax);
    float s = ms_v3f_dot(q, ax);
    for (int k = 0; k < 3; k++) n[k] = ng[k] = q[k] - s * ax[k];
    *c = s > g->join[h->primID] ? g->color2[h->primID] : g->color[h->primID];
}

const rt_prim rt_cylinder_prim = {"cylinders", cylinder_geometry, cylinder_surface};
