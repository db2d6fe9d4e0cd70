/* kernels.cl: the OpenCL tracer's kernels (OpenCL C 1.2; params.h is compiled in front).
 * One work item per pixel and one launch per sample pass. The shading is rt/shade.c's,
 * written again here line for line: each function below names the C function it mirrors,
 * and keeps its order of operations and of random numbers (rt/sample.c), so that a pass
 * without randomness gives TachyonInternal's image and a random one the same distribution.
 * What differs is the traversal: a binary BVH built on the host (bvh.c) over world-space
 * primitives (flatten.c) instead of Embree's instances, and an explicit stack of pending
 * rays instead of the recursion of rt_trace (each ray's colour enters the pixel with the
 * weight its ancestors give it: the product of opacity, mirror and fog factors). */
#pragma OPENCL FP_CONTRACT OFF

#define MINCONTRIB 0.001953125f
#define STACK 24
#define MAXDEPTH_BVH 64

typedef struct scene {
    __global const float *P;
    __global const float4 *lo0, *hi0, *lo1, *hi1;
    __global const int4 *child;
    __global const uint *leaf;
    __global const float4 *qa, *qb;
    __global const uint4 *qm;
    __global const uint4 *tri;
    __global const float4 *vxyz;
    __global const char4 *vnorm;
    __global const uchar4 *vcol;
    __global const float4 *gmat0, *gmat1;
    __global const int4 *gflag;
    __global const float4 *item;
    uint rays[4];
} scene;

/* ---------------------------------------------------------------- rt_internal.h helpers */

static float dot3(float3 a, float3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static float3 cross3(float3 a, float3 b)
{
    return (float3)(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* as ms_v3f_normalize_rcp (vecmath/vecf.h) */
static float norm3(float3 *v)
{
    float l = sqrt(dot3(*v, *v));
    if (l > 0) {
        float inv = 1.0f / l;
        *v = *v * inv;
    }
    return l;
}
static float3 vec3(__global const float *p)
{
    return (float3)(p[0], p[1], p[2]);
}
/* rt_rand, rt_randf, rt_hash2 */
static uint rt_rand(uint *s)
{
    uint x = *s = *s * 747796405u + 2891336453u;
    x = ((x >> ((x >> 28) + 4u)) ^ x) * 277803737u;
    return (x >> 22) ^ x;
}
static float rt_randf(uint *s)
{
    return (float)(rt_rand(s) >> 8) * (1.0f / 16777216.0f);
}
static uint rt_hash2(uint a, uint b)
{
    uint h = a * 0x9e3779b9u ^ (b + 0x7f4a7c15u + (a << 6) + (a >> 2));
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    return h ^ (h >> 16);
}

/* ---------------------------------------------------------------- sample.c */

static void sample_pixel(uint idx, int k, float *x, float *y)
{
    if (k == 0) {
        *x = *y = 0.5f;
        return;
    }
    uint h1 = rt_hash2(idx, 0x51f15eu), h2 = rt_hash2(idx, 0x2545f491u);
    uint u = h1 + (uint)k * 3242174889u, v = h2 + (uint)k * 2447445414u;
    *x = (float)(u >> 8) * (1.0f / 16777216.0f);
    *y = (float)(v >> 8) * (1.0f / 16777216.0f);
}

static float2 sample_disc(uint *rng)
{
    float r = sqrt(rt_randf(rng)), a = 6.2831853f * rt_randf(rng);
    return (float2)(r * cos(a), r * sin(a));
}

typedef struct hemisphere {
    float3 n, t, b;
    float r1, cs, sn;
    int count, i;
} hemisphere;

static void hemisphere_init(hemisphere *h, float3 n, int count, uint *rng)
{
    float3 a = (float3)(1.0f, 0.0f, 0.0f);
    if (fabs(n.x) > 0.5f) a = (float3)(0.0f, 1.0f, 0.0f);
    h->n = n;
    h->t = cross3(n, a);
    norm3(&h->t);
    h->b = cross3(n, h->t);
    h->count = count;
    h->i = 0;
    h->r1 = rt_randf(rng);
    float r2 = rt_randf(rng);
    h->cs = cos(6.2831853f * r2);
    h->sn = sin(6.2831853f * r2);
}

static float hemisphere_next(hemisphere *h, float3 *d)
{
    float u = ((float)h->i + h->r1) / (float)h->count;
    float r = sqrt(fmax(0.0f, 1.0f - u * u)), cs = h->cs, sn = h->sn;
    *d = r * (cs * h->t + sn * h->b) + u * h->n;
    h->cs = cs * -0.73736883f - sn * -0.67549035f;
    h->sn = sn * -0.73736883f + cs * -0.67549035f;
    h->i++;
    return u;
}

/* ---------------------------------------------------------------- camera.c */

static void camera_ray(__global const float *P, float px, float py, const float2 *lens,
                       float3 *org, float3 *dir)
{
    float sx = (2.0f * px / P[P_WIDTH] - 1.0f) * P[P_HALF_W];
    float sy = (1.0f - 2.0f * py / P[P_HEIGHT]) * P[P_HALF_H];
    float3 eye = vec3(P + P_EYE), cd = vec3(P + P_DIR), right = vec3(P + P_RIGHT), up = vec3(P + P_UP);
    if (P[P_ORTHO] != 0.0f) {
        *org = eye + sx * right + sy * up;
        *dir = cd;
        return;
    }
    *org = eye;
    *dir = cd + sx * right + sy * up;
    norm3(dir);
    if (!lens || P[P_DOF] == 0.0f) return;
    float3 focus = *org + P[P_FOCAL] * *dir;
    *org = *org + P[P_LENS_RADIUS] * (lens->x * right + lens->y * up);
    *dir = focus - *org;
    norm3(dir);
}

/* ---------------------------------------------------------------- primitive tests */

/* sphere.c's sphere_test: both crossings in (tnear, tfar), nearest first. */
static int sphere_test(float4 c, float3 o, float3 d, float tnear, float tfar, float *t)
{
    float rad = c.w;
    float3 oc = c.xyz - o;
    float inv = 1.0f / dot3(d, d), tc = dot3(oc, d) * inv;
    float3 q = oc - tc * d;
    float l2 = dot3(q, q);
    if (l2 > rad * rad) return 0;
    float td = sqrt((rad * rad - l2) * inv);
    int n = 0;
    if (tc - td > tnear && tc - td < tfar) t[n++] = tc - td;
    if (tc + td > tnear && tc + td < tfar) t[n++] = tc + td;
    return n;
}

/* cylinder.c's cylinder_test: a = base and radius, ax = unit axis and length. */
static int cylinder_test(float4 a, float4 ax, float3 o, float3 d, float tnear, float tfar, float *t)
{
    float rad = a.w;
    float3 oc = o - a.xyz, axis = ax.xyz;
    float ds = dot3(d, axis), ocs = dot3(oc, axis);
    float3 dp = d - ds * axis, ocp = oc - ocs * axis;
    float qa = dot3(dp, dp);
    if (!(qa > 0.0f)) return 0;
    float inv = 1.0f / qa, tc = -dot3(ocp, dp) * inv;
    float3 q = ocp + tc * dp;
    float l2 = dot3(q, q);
    if (l2 > rad * rad) return 0;
    float td = sqrt((rad * rad - l2) * inv), roots[2] = {tc - td, tc + td};
    int n = 0;
    for (int k = 0; k < 2; k++) {
        float s = ocs + roots[k] * ds;
        if (roots[k] > tnear && roots[k] < tfar && s >= 0.0f && s <= ax.w) t[n++] = roots[k];
    }
    return n;
}

/* user.c's rt_quadratic */
static int quadratic(float a, float b, float c, float *t0, float *t1)
{
    float disc = b * b - a * c;
    if (!(disc >= 0.0f)) return 0;
    float q = -(b + copysign(sqrt(disc), b));
    float r0 = c / q, r1 = q / a;
    if (q == 0.0f) r0 = r1;
    *t0 = fmin(r0, r1);
    *t1 = fmax(r0, r1);
    return 1;
}

/* cone.c's cone_test: a = base and its radius, b = apex and its radius. */
static int cone_test(float4 a, float4 b, float3 o, float3 d, float tnear, float tfar, float *t)
{
    float3 A = a.xyz, B = b.xyz, ax = B - A;
    float ra = a.w, len = norm3(&ax), k = (b.w - ra) / len;
    float3 mid = 0.5f * (A + B) - o;
    float dd = dot3(d, d), t0 = dot3(mid, d) / dd;
    float3 oc = o + t0 * d - A;
    float ds = dot3(d, ax), ocs = dot3(oc, ax), r0 = ra + k * ocs;
    float qa = dd - ds * ds - k * k * ds * ds;
    float qb = dot3(oc, d) - ocs * ds - k * ds * r0;
    float qc = dot3(oc, oc) - ocs * ocs - r0 * r0, roots[2];
    if (fabs(qa) < 1e-12f * dd) {
        if (qb == 0.0f) return 0;
        roots[0] = -0.5f * qc / qb;
        roots[1] = INFINITY;
    } else if (!quadratic(qa, qb, qc, &roots[0], &roots[1])) {
        return 0;
    }
    int n = 0;
    for (int j = 0; j < 2; j++) {
        float tt = t0 + roots[j], s = ocs + roots[j] * ds;
        if (tt > tnear && tt < tfar && s >= 0.0f && s <= len && ra + k * s >= 0.0f) t[n++] = tt;
    }
    return n;
}

/* ring.c's ring_test: a = centre and outer radius, b = normal (any length) and inner radius. */
static int ring_test(float4 a, float4 b, float3 o, float3 d, float tnear, float tfar, float *t)
{
    float3 n = b.xyz;
    norm3(&n);
    float den = dot3(d, n);
    if (den == 0.0f) return 0;
    float3 co = a.xyz - o;
    float tt = dot3(co, n) / den;
    if (!(tt > tnear && tt < tfar)) return 0;
    float3 q = tt * d - co;
    float d2 = dot3(q, q);
    if (d2 > a.w * a.w || d2 < b.w * b.w) return 0;
    t[0] = tt;
    return 1;
}

/* A triangle (Moller-Trumbore); u and v weigh the second and third vertices, as Embree's. */
static int triangle_test(float3 v0, float3 v1, float3 v2, float3 o, float3 d, float tnear,
                         float tfar, float *t, float *u, float *v)
{
    float3 e1 = v1 - v0, e2 = v2 - v0, pv = cross3(d, e2);
    float det = dot3(e1, pv);
    if (det == 0.0f || !isfinite(det)) return 0;
    float inv = 1.0f / det;
    float3 tv = o - v0;
    float uu = dot3(tv, pv) * inv;
    if (uu < 0.0f || uu > 1.0f) return 0;
    float3 qv = cross3(tv, e1);
    float vv = dot3(d, qv) * inv;
    if (vv < 0.0f || uu + vv > 1.0f) return 0;
    float tt = dot3(e2, qv) * inv;
    if (!(tt > tnear && tt < tfar)) return 0;
    *t = tt, *u = uu, *v = vv;
    return 1;
}

/* The crossings of primitive ref in (tnear, tfar), nearest first; u, v for triangles. */
static int prim_test(const scene *S, uint ref, float3 o, float3 d, float tnear, float tfar,
                     float *t, float *u, float *v)
{
    uint kind = ref >> ORC_KIND_SHIFT, i = ref & ORC_INDEX_MASK;
    if (kind == ORC_TRIANGLE) {
        uint4 tr = S->tri[i];
        return triangle_test(S->vxyz[tr.x].xyz, S->vxyz[tr.y].xyz, S->vxyz[tr.z].xyz, o, d, tnear,
                             tfar, t, u, v);
    }
    *u = *v = 0.0f;
    float4 a = S->qa[i], b = S->qb[i];
    if (kind == ORC_SPHERE) return sphere_test(a, o, d, tnear, tfar, t);
    if (kind == ORC_CYLINDER) return cylinder_test(a, b, o, d, tnear, tfar, t);
    if (kind == ORC_CONE) return cone_test(a, b, o, d, tnear, tfar, t);
    return ring_test(a, b, o, d, tnear, tfar, t);
}

/* The geometry of primitive ref. */
static uint prim_geom(const scene *S, uint ref)
{
    uint i = ref & ORC_INDEX_MASK;
    return ref >> ORC_KIND_SHIFT == ORC_TRIANGLE ? S->tri[i].w : S->qm[i].x;
}

/* user.c's rt_geom_opacity: the material's opacity times the colour's alpha (a mesh's
 * interpolated at u, v). */
static float prim_opacity(const scene *S, uint ref, float u, float v)
{
    uint kind = ref >> ORC_KIND_SHIFT, i = ref & ORC_INDEX_MASK;
    uint g = prim_geom(S, ref);
    float op = S->gmat1[g].y;
    if (!S->gflag[g].y) return op;
    float a;
    if (kind == ORC_TRIANGLE) {
        uint4 tr = S->tri[i];
        a = (1.0f - u - v) * (float)S->vcol[tr.x].w + u * (float)S->vcol[tr.y].w +
            v * (float)S->vcol[tr.z].w;
    } else {
        a = (float)as_uchar4(S->qm[i].y).w;
    }
    return op * a * (1.0f / 255.0f);
}

/* user.c's rt_geom_clipped (scene.h's ms_scene_clipped): is world point p cut away by a
 * clip plane of geometry g's item? */
static int clipped(const scene *S, uint g, float3 p)
{
    int4 f = S->gflag[g];
    for (int i = 0; i < f.w; i++) {
        float4 e = S->item[ORC_ITEM * f.z + ORC_ITEM_PLANES + i];
        if (e.x * p.x + e.y * p.y + e.z * p.z + e.w < 0.0f) return 1;
    }
    return 0;
}

/* The n crossings t[] of primitive ref less those its clip planes cut away (shade.c's
 * intersect_unclipped passes them and goes on; occlusion rays pass them too): how many are
 * left, nearest first in t[]. */
static int unclipped(const scene *S, uint ref, float3 o, float3 d, float *t, int n)
{
    uint g = prim_geom(S, ref);
    if (S->gflag[g].w == 0) return n;
    int kept = 0;
    for (int k = 0; k < n; k++)
        if (!clipped(S, g, o + t[k] * d)) t[kept++] = t[k];
    return kept;
}

/* ---------------------------------------------------------------- traversal */

/* The ray's entry distance into a box, or INFINITY when it misses it within (tnear, tfar). */
static float box_hit(float4 lo, float4 hi, float3 o, float3 inv, float tnear, float tfar)
{
    float3 t0 = (lo.xyz - o) * inv, t1 = (hi.xyz - o) * inv;
    float3 mn = fmin(t0, t1), mx = fmax(t0, t1);
    float a = fmax(fmax(mn.x, mn.y), fmax(mn.z, tnear)), b = fmin(fmin(mx.x, mx.y), fmin(mx.z, tfar));
    return a <= b ? a : INFINITY;
}

/* Walk the tree: closest (any == 0: the nearest hit in *t, *ref, *u, *v) or visibility
 * (any == 1: the light left after the transparent crossings, 0 at an opaque one, as
 * rt_user_block and rt_occlusion_filter count them); both pass the crossings a clip plane
 * cut away. Returns whether something was hit (closest) or the light left (visibility). */
static float traverse(const scene *S, float3 o, float3 d, float tnear, int any, float *t, uint *ref,
                      float *u, float *v)
{
    int stack[MAXDEPTH_BVH], sp = 0, node = 0, nnodes = (int)S->P[P_NNODES];
    int clips = S->P[P_CLIPPED] != 0.0f;
    float3 inv = 1.0f / d;
    float tfar = INFINITY, f = 1.0f;
    int hit = 0;
    if (nnodes == 0) return any ? 1.0f : 0.0f;
    for (;;) {
        int4 c = S->child[node];
        int go[2] = {-1, -1};
        float enter[2] = {INFINITY, INFINITY};
        for (int k = 0; k < 2; k++) {
            int r = k ? c.y : c.x, cnt = k ? c.w : c.z;
            if (r < 0) continue;
            float4 lo = k ? S->lo1[node] : S->lo0[node], hi = k ? S->hi1[node] : S->hi0[node];
            enter[k] = box_hit(lo, hi, o, inv, tnear, tfar);
            if (enter[k] == INFINITY) continue;
            if (cnt == 0) {
                go[k] = r;
                continue;
            }
            for (int p = r; p < r + cnt; p++) {
                uint pr = S->leaf[p];
                float tt[2], uu, vv;
                int n = prim_test(S, pr, o, d, tnear, tfar, tt, &uu, &vv);
                if (n && clips) n = unclipped(S, pr, o, d, tt, n);
                if (!n) continue;
                if (!any) {
                    tfar = tt[0], *t = tt[0], *ref = pr, *u = uu, *v = vv, hit = 1;
                    continue;
                }
                float op = prim_opacity(S, pr, uu, vv);
                if (op >= 1.0f) return 0.0f;
                f *= n == 2 ? (1.0f - op) * (1.0f - op) : 1.0f - op;
            }
        }
        if (go[0] >= 0 && go[1] >= 0) {     /* the nearer box first */
            int near = enter[1] < enter[0];
            if (sp < MAXDEPTH_BVH) stack[sp++] = go[1 - near];
            node = go[near];
        } else if (go[0] >= 0 || go[1] >= 0) {
            node = go[0] >= 0 ? go[0] : go[1];
        } else if (sp > 0) {
            node = stack[--sp];
        } else {
            break;
        }
    }
    return any ? f : (float)hit;
}

/* ---------------------------------------------------------------- shade.c */

/* shade.c's background */
static float3 background(__global const float *P, float3 org, float3 dir)
{
    int mode = (int)P[P_BG_MODE];
    if (mode == ORC_BG_SOLID) return vec3(P + P_BG);
    float v = mode == ORC_BG_SKY_SPHERE ? dir.y : org.y;
    v = (v - P[P_GRAD_BOT]) / (P[P_GRAD_TOP] - P[P_GRAD_BOT]);
    v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
    return v * vec3(P + P_BG_TOP) + (1.0f - v) * vec3(P + P_BG_BOT);
}

/* shade.c's fog: the factor of the surface's colour (the rest is the background's). */
static float fog_factor(__global const float *P, float z)
{
    float f;
    int mode = (int)P[P_CUEMODE];
    if (mode == ORC_CUE_LINEAR) {
        f = (P[P_FOG_END] - z) / (P[P_FOG_END] - P[P_FOG_START]);
    } else {
        float v = P[P_FOG_DENSITY] * (z - P[P_FOG_START]);
        f = exp(mode == ORC_CUE_EXP ? -v : -v * v);
    }
    return f > 1.0f ? 1.0f : f < 0.0f ? 0.0f : f;
}

/* shade.c's ray_ok */
static int ray_ok(float3 o, float3 d)
{
    if (!(fabs(o.x) <= 1e18f && fabs(o.y) <= 1e18f && fabs(o.z) <= 1e18f)) return 0;
    if (!(fabs(d.x) <= 1e18f && fabs(d.y) <= 1e18f && fabs(d.z) <= 1e18f)) return 0;
    return d.x != 0 || d.y != 0 || d.z != 0;
}

typedef struct surface {
    float3 p, n, col;
    float t, opacity;
    uint g;
} surface;

static uchar mix8(uchar a, uchar b, uchar c, float wa, float wb, float wc)
{
    float v = wa * a + wb * b + wc * c + 0.5f;
    return (uchar)(v < 0.0f ? 0.0f : v > 255.0f ? 255.0f : v);
}

static float dequant(char c)
{
    return (2.0f * (float)c + 1.0f) * (1.0f / 255.0f);
}

/* shade.c's solid_cut: the inside of a surface seen through a cut of a solid clip plane
 * (VMD's status 2) takes the plane's colour and faces the viewer as the plane does. */
static void solid_cut(const scene *S, float3 d, surface *s)
{
    int4 f = S->gflag[s->g];
    for (int i = 0; i < f.w; i++) {
        float4 c = S->item[ORC_ITEM * f.z + ORC_ITEM_COLORS + i];
        if (c.w == 0.0f) continue;
        float3 n = S->item[ORC_ITEM * f.z + ORC_ITEM_PLANES + i].xyz;
        if (!(norm3(&n) > 0.0f)) continue;
        float side = dot3(n, d) > 0.0f ? -1.0f : 1.0f;
        s->n = side * n;
        s->col = c.xyz;
        return;
    }
}

/* shade.c's surface_at with the primitive files' surface functions (world space here). */
static void surface_at(const scene *S, float3 o, float3 d, float t, uint ref, float u, float v,
                       surface *s)
{
    uint kind = ref >> ORC_KIND_SHIFT, i = ref & ORC_INDEX_MASK;
    float3 n, ng;
    uchar4 c;
    s->t = t;
    s->p = o + t * d;
    if (kind == ORC_TRIANGLE) {
        uint4 tr = S->tri[i];
        float wb = u, wc = v, wa = 1.0f - wb - wc;
        char4 na = S->vnorm[tr.x], nb = S->vnorm[tr.y], nc = S->vnorm[tr.z];
        float3 nl = (float3)(wa * dequant(na.x) + wb * dequant(nb.x) + wc * dequant(nc.x),
                             wa * dequant(na.y) + wb * dequant(nb.y) + wc * dequant(nc.y),
                             wa * dequant(na.z) + wb * dequant(nb.z) + wc * dequant(nc.z));
        int it = S->gflag[tr.w].z;
        __global const float4 *m = S->item + ORC_ITEM * it;
        float4 m0 = m[0], m1 = m[1], m2 = m[2];
        n = (float3)(dot3(m0.xyz, nl), dot3(m1.xyz, nl), dot3(m2.xyz, nl));
        float3 v0 = S->vxyz[tr.x].xyz;
        ng = cross3(S->vxyz[tr.y].xyz - v0, S->vxyz[tr.z].xyz - v0) * m0.w;
        uchar4 ca = S->vcol[tr.x], cb = S->vcol[tr.y], cc = S->vcol[tr.z];
        c = (uchar4)(mix8(ca.x, cb.x, cc.x, wa, wb, wc), mix8(ca.y, cb.y, cc.y, wa, wb, wc),
                     mix8(ca.z, cb.z, cc.z, wa, wb, wc), mix8(ca.w, cb.w, cc.w, wa, wb, wc));
        s->g = tr.w;
    } else {
        float4 a = S->qa[i], b = S->qb[i];
        uint4 m = S->qm[i];
        if (kind == ORC_SPHERE) {
            n = s->p - a.xyz;
        } else if (kind == ORC_CYLINDER) {
            float3 q = s->p - a.xyz;
            float sc = dot3(q, b.xyz);
            n = q - sc * b.xyz;
            if (sc > as_float(m.w)) m.y = m.z;   /* beyond a bond's joint: its second colour */
        } else if (kind == ORC_CONE) {
            float3 ax = b.xyz - a.xyz, q = s->p - a.xyz;
            float len = norm3(&ax), k = (b.w - a.w) / len, sc = dot3(q, ax);
            float3 perp = q - sc * ax;
            norm3(&perp);
            n = perp - k * ax;
        } else {
            n = b.xyz;
        }
        ng = n;
        c = as_uchar4(m.y);
        s->g = m.x;
    }
    float side = dot3(ng, d) > 0.0f ? -1.0f : 1.0f;
    s->n = n;
    if (!(norm3(&s->n) > 0.0f) || !isfinite(s->n.x + s->n.y + s->n.z)) {
        s->n = d;
        side = -1.0f;
    }
    s->n = s->n * side;
    s->col = (float3)(c.x * (1.0f / 255.0f), c.y * (1.0f / 255.0f), c.z * (1.0f / 255.0f));
    if (side < 0.0f) solid_cut(S, d, s);
    s->opacity = S->gmat1[s->g].y * (float)c.w * (1.0f / 255.0f);
}

/* shade.c's visibility */
static float visibility(scene *S, float3 p, float3 d, int kind)
{
    float t, u, v;
    uint ref;
    if (!ray_ok(p, d)) return 0.0f;
    S->rays[kind]++;
    return traverse(S, p, d, S->P[P_EPS], 1, &t, &ref, &u, &v);
}

/* shade.c's occlusion */
static float3 occlusion(scene *S, const surface *s, uint *rng)
{
    hemisphere h;
    int count = (int)S->P[P_AO_SAMPLES];
    hemisphere_init(&h, s->n, count, rng);
    float sum = 0.0f;
    for (int i = 0; i < count; i++) {
        float3 d;
        float cosine = hemisphere_next(&h, &d);
        sum += cosine * visibility(S, s->p, d, 2);
    }
    return 2.0f / (float)count * sum * vec3(S->P + P_AO_COL);
}

/* shade.c's blinn */
static float blinn(float3 n, float3 l, float3 d, float exponent)
{
    float3 h = l - d;
    float i = dot3(n, h);
    if (!(i > MINCONTRIB)) return 0.0f;
    return pow(i / sqrt(dot3(h, h)), exponent);
}

/* shade.c's direct */
static void direct(scene *S, const surface *s, float3 dir, uint *rng, float3 *diffuse, float3 *phong)
{
    __global const float *P = S->P;
    float4 m0 = S->gmat0[s->g], m1 = S->gmat1[s->g];
    *diffuse = *phong = (float3)(0.0f);
    if (!(m0.y > MINCONTRIB || m0.w > MINCONTRIB)) return;
    int full = P[P_FULL] != 0.0f;
    float scale = P[P_LIGHT_SCALE];
    for (int i = 0; i < (int)P[P_NLIGHTS]; i++) {
        float3 l = vec3(P + P_LDIR + 3 * i);
        float inten = scale * dot3(s->n, l);
        if (!(inten > MINCONTRIB)) continue;
        if (full) {
            float v = visibility(S, s->p, l, 1);
            if (v <= 0.0f) continue;
            inten *= v;
        }
        float pv = m0.w > MINCONTRIB ? scale * blinn(s->n, l, dir, m1.x) * m0.w : 0.0f;
        float3 lc = vec3(P + P_LCOL + 3 * i);
        *diffuse += inten * lc;
        *phong += pv * lc;
    }
    if (full && P[P_AO_SAMPLES] > 0.0f) *diffuse += occlusion(S, s, rng);
}

typedef struct task {
    float3 o, d;
    float w;
    int depth;
} task;

/* shade.c's rt_trace and shade, without recursion: a ray's colour is
 * fog (a (local + mirror M) + (1 - a) T) + (1 - fog) background, linear in the colours M and
 * T of its reflected and transmitted rays, so each pending ray carries the weight its
 * ancestors give it. Rays are taken depth first, the mirror ray before the transmitted one,
 * as the recursion takes them, so the random numbers go to the same rays. */
static float3 trace(scene *S, float3 org, float3 dir, uint *rng)
{
    __global const float *P = S->P;
    task st[STACK];
    int sp = 0;
    float3 out = (float3)(0.0f);
    st[sp++] = (task){org, dir, 1.0f, (int)P[P_DEPTH]};
    int primary = 1;
    while (sp > 0) {
        task k = st[--sp];
        float t, u, v;
        uint ref;
        if (!ray_ok(k.o, k.d)) {
            out += k.w * vec3(P + P_BG);
            primary = 0;
            continue;
        }
        float hit = traverse(S, k.o, k.d, primary ? 0.0f : P[P_EPS], 0, &t, &ref, &u, &v);
        S->rays[primary ? 0 : 3]++;
        if (hit == 0.0f) {
            out += k.w * background(P, k.o, k.d);
            primary = 0;
            continue;
        }
        surface s;
        surface_at(S, k.o, k.d, t, ref, u, v, &s);
        float4 m0 = S->gmat0[s.g], m1 = S->gmat1[s.g];
        float3 diffuse, phong;
        float nd = dot3(s.n, k.d), f = m0.y;
        direct(S, &s, k.d, rng, &diffuse, &phong);
        if (m1.z > 0.0f) {
            float e = 1.0f - pow(1.0f - nd * nd, (1.0f - m1.w) * 32.0f);
            f *= (1.0f - m1.z) + e * m1.z;
        }
        float3 own = s.col * (diffuse * f + m0.x) + phong;
        float a = 1.0f, fg = 1.0f;
        int trans = s.opacity < 1.0f - MINCONTRIB, mirror = m0.z > MINCONTRIB;
        if (trans) {
            a = s.opacity;
            if (S->gflag[s.g].x) {
                a = 1.0f + cos(3.1415926f * (1.0f - a) * nd);
                a = a * a * 0.25f;
            }
        }
        if (P[P_FOG] != 0.0f) {
            fg = fog_factor(P, primary ? s.t * dot3(k.d, vec3(P + P_DIR)) : s.t);
            out += k.w * (1.0f - fg) * vec3(P + P_BG);
        }
        primary = 0;
        out += k.w * fg * a * own;
        float wm = k.w * fg * a * m0.z, wt = k.w * fg * (1.0f - a);
        if (k.depth <= 1) {     /* shade.c's secondary: the background once depth runs out */
            float3 bg = background(P, k.o, k.d);
            if (mirror) out += wm * bg;
            if (trans) out += wt * bg;
            continue;
        }
        if (trans && sp < STACK) st[sp++] = (task){s.p, k.d, wt, k.depth - 1};
        if (mirror && sp < STACK) st[sp++] = (task){s.p, k.d - 2.0f * nd * s.n, wm, k.depth - 1};
    }
    return out;
}

/* ---------------------------------------------------------------- kernels */

/* Before the first pass: empty sums and counts, each pixel's random state (frame.c's seed). */
__kernel void orc_init(__global float *accum, __global uint *rng, __global uint4 *rays, uint npix)
{
    uint idx = get_global_id(0);
    if (idx >= npix) return;
    accum[3 * idx] = accum[3 * idx + 1] = accum[3 * idx + 2] = 0.0f;
    rng[idx] = rt_hash2(idx, 0x6d2b79f5u);
    rays[idx] = (uint4)(0u);
}

/* One pass: frame.c's trace_tile for every pixel. */
__kernel void orc_pass(__global const float *P, __global const float4 *lo0,
                       __global const float4 *hi0, __global const float4 *lo1,
                       __global const float4 *hi1, __global const int4 *child,
                       __global const uint *leaf, __global const float4 *qa,
                       __global const float4 *qb, __global const uint4 *qm,
                       __global const uint4 *tri, __global const float4 *vxyz,
                       __global const char4 *vnorm, __global const uchar4 *vcol,
                       __global const float4 *gmat0, __global const float4 *gmat1,
                       __global const int4 *gflag, __global const float4 *item,
                       __global float *accum, __global uint *rng, __global uint4 *rays,
                       int pass)
{
    int width = (int)P[P_WIDTH], height = (int)P[P_HEIGHT];
    uint idx = get_global_id(0);
    if (idx >= (uint)width * (uint)height) return;
    scene S = {P, lo0, hi0, lo1, hi1, child, leaf, qa, qb, qm, tri, vxyz, vnorm, vcol,
               gmat0, gmat1, gflag, item, {0u, 0u, 0u, 0u}};
    int x = (int)(idx % (uint)width), y = (int)(idx / (uint)width);
    uint s = rng[idx];
    float sx, sy;
    float2 lens = (float2)(0.0f);
    float3 org, dir;
    sample_pixel(idx, pass, &sx, &sy);
    if (pass > 0) lens = sample_disc(&s);
    camera_ray(P, (float)x + sx, (float)y + sy, pass > 0 ? &lens : 0, &org, &dir);
    float3 col = trace(&S, org, dir, &s);
    accum[3 * idx] += isfinite(col.x) ? col.x : 0.0f;
    accum[3 * idx + 1] += isfinite(col.y) ? col.y : 0.0f;
    accum[3 * idx + 2] += isfinite(col.z) ? col.z : 0.0f;
    rng[idx] = s;
    rays[idx] += (uint4)(S.rays[0], S.rays[1], S.rays[2], S.rays[3]);
}
