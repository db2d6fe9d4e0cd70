/* cylinder.c: open cylinders (Tachyon's FCylinder), an Embree user geometry: the tube between
 * the base and apex centres, both of its surfaces (a ray can see the inside of an open end).
 * Closed ends are discs (ring.c). Each cylinder's unit axis and length are worked out once,
 * at the build, for the tests. Two half cylinders that make one tube (a bond drawn in its
 * two atoms' colours: the same radius and alpha, apexes meeting, on one line) are traced as
 * one cylinder whose colour changes at the joint: the same surface with half the primitives
 * to build and test (on the benchmark's Licorice, 981k halves become 491k tubes). */
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
        o[3] = ms_v3f_normalize_rcp(o);
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

/* ---------------------------------------------------------------- joining halves */

#define NO_MATE UINT32_MAX

/* Whether cylinders i and j are the halves of one tube: the same radius and alpha, the
 * apexes the same point, the bases on opposite sides of it on one line. */
static int halves(const rt_geom *g, size_t i, size_t j)
{
    const float *ai = g->a + 3 * i, *bi = g->b + 3 * i, *aj = g->a + 3 * j, *bj = g->b + 3 * j;
    if (g->ra[i] != g->ra[j] || g->color[i].a != g->color[j].a || memcmp(bi, bj, 3 * sizeof(float)))
        return 0;
    float u[3] = {bi[0] - ai[0], bi[1] - ai[1], bi[2] - ai[2]};
    float v[3] = {aj[0] - bj[0], aj[1] - bj[1], aj[2] - bj[2]}, c[3];
    float uu = ms_v3f_dot(u, u), vv = ms_v3f_dot(v, v), uv = ms_v3f_dot(u, v);
    if (!(uu > 0.0f && vv > 0.0f && uv > 0.0f && isfinite(uu * vv))) return 0;
    ms_v3f_cross(u, v, c);
    return ms_v3f_dot(c, c) <= 1e-8f * uu * vv;    /* parallel to float rounding of the joint */
}

static size_t apex_slot(const rt_geom *g, size_t i, size_t mask)
{
    uint32_t u[4];
    memcpy(u, g->b + 3 * i, 3 * sizeof(float));
    memcpy(u + 3, g->ra + i, sizeof(float));
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int k = 0; k < 4; k++) {
        h = (h ^ u[k]) * 0xff51afd7ed558ccdull;
        h ^= h >> 32;
    }
    return (size_t)h & mask;
}

/* Pair the halves: mate[i] is i's other half or NO_MATE. Halves next to each other in the
 * list are paired directly, others through a hash table of unpaired apexes. Returns the
 * number of pairs, or -1 when out of memory. */
static long pair_halves(const rt_geom *g, uint32_t *mate)
{
    size_t cap = 1;
    while (cap < 2 * g->n) cap *= 2;
    uint32_t *tab = malloc(cap * sizeof *tab);
    if (!tab) return -1;
    memset(tab, 0xff, cap * sizeof *tab);
    long pairs = 0;
    for (size_t i = 0; i < g->n; i++) mate[i] = NO_MATE;
    for (size_t i = 0; i < g->n; i++) {
        if (mate[i] != NO_MATE) continue;
        if (i + 1 < g->n && halves(g, i, i + 1)) {
            mate[i] = (uint32_t)(i + 1), mate[i + 1] = (uint32_t)i, pairs++;
            continue;
        }
        size_t s = apex_slot(g, i, cap - 1);
        for (; tab[s] != NO_MATE; s = (s + 1) & (cap - 1)) {
            uint32_t j = tab[s];
            if (mate[j] == NO_MATE && halves(g, j, i)) {
                mate[i] = j, mate[j] = (uint32_t)i, pairs++;
                break;
            }
        }
        if (mate[i] == NO_MATE) tab[s] = (uint32_t)i;
    }
    free(tab);
    return pairs;
}

typedef struct joined {
    const rt_geom *g;
    const uint32_t *first, *mate;   /* each tube's first half; its other half */
    float *a, *b, *ra, *join;
    ms_rgba8 *col, *col2;
} joined;

static void join_range(void *ctx, size_t b, size_t e, int thread)
{
    const joined *x = ctx;
    const rt_geom *g = x->g;
    for (size_t k = b; k < e; k++) {
        size_t i = x->first[k], j = x->mate[i];
        const float *end = j == NO_MATE ? g->b + 3 * i : g->a + 3 * j;
        float d[3];
        for (int c = 0; c < 3; c++) {
            x->a[3 * k + c] = g->a[3 * i + c];
            x->b[3 * k + c] = end[c];
            d[c] = g->b[3 * i + c] - g->a[3 * i + c];
        }
        x->ra[k] = g->ra[i];
        x->col[k] = g->color[i];
        x->col2[k] = j == NO_MATE ? g->color[i] : g->color[j];
        x->join[k] = j == NO_MATE ? INFINITY : sqrtf(ms_v3f_dot(d, d));
    }
}

/* Replace g's cylinders by the tubes of its paired halves (g untouched when none pair). */
static int join_halves(rt_world *w, rt_geom *g, ms_error *err)
{
    uint32_t *mate = malloc(g->n * sizeof *mate), *first = NULL;
    long pairs = mate ? pair_halves(g, mate) : -1;
    if (pairs > 0) first = malloc((g->n - (size_t)pairs) * sizeof *first);
    if (pairs < 0 || (pairs > 0 && !first)) {
        free(mate);
        ms_error_set(err, "cylinders: out of memory");
        return -1;
    }
    if (pairs == 0) {
        free(mate);
        return 0;
    }
    size_t m = 0;
    for (size_t i = 0; i < g->n; i++)
        if (mate[i] == NO_MATE || mate[i] > i) first[m++] = (uint32_t)i;
    joined x = {g, first, mate, rt_world_alloc(w, 3 * m, sizeof(float), err),
                rt_world_alloc(w, 3 * m, sizeof(float), err), rt_world_alloc(w, m, sizeof(float), err),
                rt_world_alloc(w, m, sizeof(float), err), rt_world_alloc(w, m, sizeof(ms_rgba8), err),
                rt_world_alloc(w, m, sizeof(ms_rgba8), err)};
    int ok = x.a && x.b && x.ra && x.join && x.col && x.col2;
    if (ok) ms_parallel_for(m, 65536, join_range, &x);
    free(mate);
    free(first);
    if (!ok) return -1;
    g->n = m, g->a = x.a, g->b = x.b, g->ra = x.ra, g->join = x.join;
    g->color = x.col, g->color2 = x.col2;
    return 0;
}

/* ---------------------------------------------------------------- spheres on the ends */

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
    for (size_t s = point_slot(p, mask); tab[s] != NO_MATE; s = (s + 1) & mask) {
        uint32_t j = tab[s];
        if (!g->taken[j] && !memcmp(sp->xyz + 3 * (size_t)j, p, 3 * sizeof(float)) &&
            sp->color[j].a == g->color[i].a)
            return j;
    }
    return NO_MATE;
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
        while (tab[s] != NO_MATE) s = (s + 1) & (cap - 1);
        tab[s] = (uint32_t)j;
    }
    for (size_t i = 0; i < g->n; i++)
        for (int e = 0; e < 2; e++) {
            const float *p = (e ? g->b : g->a) + 3 * i;
            float *o = ends + 8 * i + 4 * e;
            uint32_t j = tube_ok(g, i) ? free_sphere(g, tab, cap - 1, p, i) : NO_MATE;
            memcpy(o, p, 3 * sizeof(float));
            o[3] = 0.0f;
            col[2 * i + e] = g->color[i];
            if (j == NO_MATE) continue;
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

/* The crossings of the cylinder and of its end spheres: how many, and the nearest with its
 * part (0 the tube, 1 the base sphere, 2 the far sphere). */
static int capsule_test(const rt_geom *g, unsigned prim, const rt_uray *r, float *near, int *part)
{
    float t[2];
    int n = cylinder_test(g, prim, r, t), total = n;
    *near = n ? t[0] : INFINITY;
    *part = 0;
    for (int e = 0; e < 2; e++) {
        const float *c = g->ends + 8 * (size_t)prim + 4 * e;
        if (!(c[3] > 0.0f)) continue;
        n = rt_sphere_hits(c, c[3], r, t);
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
        if (capsule_test(g, args->primID, &r, &t, &part)) rt_user_hit_part(args, i, t, (float)part);
    }
}

static void capsule_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    for (unsigned i = 0; i < args->N; i++) {
        rt_uray r;
        float t;
        int part;
        if (!args->valid[i]) continue;
        rt_user_ray((const float *)args->ray, args->N, i, &r);
        int n = capsule_test(g, args->primID, &r, &t, &part);
        if (n) rt_user_block(args, i, n, &r);
    }
}

static RTCGeometry cylinder_geometry(rt_world *w, rt_geom *g, ms_error *err)
{
    if (join_halves(w, g, err)) return NULL;
    if (g->spheres && g->spheres->n && take_spheres(w, g, err)) return NULL;
    axes x = {g, rt_world_alloc(w, 4 * g->n, sizeof(float), err)};
    if (!x.aux) return NULL;
    ms_parallel_for(g->n, 65536, axes_range, &x);
    g->aux = x.aux;
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
    *c = g->color2 && s > g->join[h->primID] ? g->color2[h->primID] : g->color[h->primID];
}

const rt_prim rt_cylinder_prim = {"cylinders", cylinder_geometry, cylinder_surface};
