/* cull.c: occlusion culling of sphere, cylinder and cone impostors on the CPU, before they
 * reach GL. In a dense million-atom scene most atoms lie behind others; on llvmpipe every
 * primitive costs front-end time whether it shows or not, so dropping the hidden ones first
 * makes the draw several times faster. The image does not change: culling is conservative.
 *
 * Distances are measured along the eye ray (from the eye under perspective, from the eye
 * plane under orthographic projection). An opaque sphere wholly between the clip planes is
 * drawn at every pixel whose ray meets it, at the distance of the first hit. Each pixel
 * whose ray meets the ball well inside its rim receives that distance (computed in double
 * precision, nudged farther) in an occlusion buffer (the smallest wins; the store is a
 * relaxed atomic, and a lost race only leaves another occluder's value, still a valid
 * bound). Cylinders add the balls
 * inscribed along their axis. A primitive is then hidden when, at every pixel centre its
 * screen rectangle may sample (the shaders widen rectangles by RECT_MARGIN against subpixel
 * snapping), either the pixel's ray misses the capsule around it (its end balls swept along
 * the axis, slightly widened) or the capsule lies beyond the buffer along that ray. A
 * primitive whose rectangle holds no pixel centre draws nothing: it goes too (most atoms of
 * a million-atom Licorice view are smaller than a pixel). */
#include "config.h"
#include "gl/glrender.h"
#include "base/threads.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#define CHUNK 16384
#define TEST_MAX_PIXELS 4096      /* larger rectangles are kept without a test */
#define RECT_MARGIN 0.05f         /* pixels the shaders widen screen rectangles by */

struct ms_glcull {
    ms_glcam cam;
    float px_per_unit;            /* pixels per image-plane (or orthographic) unit */
    _Atomic uint32_t *occ;        /* float bits of the nearest occluder distance per pixel */
};

ms_glcull *ms_glcull_new(const ms_glcam *cam, ms_error *err)
{
    ms_glcull *c = calloc(1, sizeof *c);
    size_t n = (size_t)cam->width * (size_t)cam->height;
    if (c) c->occ = ms_alloc_array(n, sizeof *c->occ);
    if (!c || !c->occ) {
        free(c);
        ms_error_set(err, "out of memory");
        return NULL;
    }
    c->cam = *cam;
    c->px_per_unit = 0.5f * (float)cam->height / cam->hy;
    float inf = INFINITY;
    uint32_t bits;
    memcpy(&bits, &inf, sizeof bits);
    for (size_t i = 0; i < n; i++) atomic_init(&c->occ[i], bits);
    return c;
}

void ms_glcull_free(ms_glcull *c)
{
    if (!c) return;
    free(c->occ);
    free(c);
}

static void xform(const float m[16], const float p[3], float out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
}

/* Window position (pixels, GL's: y up) of an eye-space point in front of the eye. */
static void to_window(const ms_glcull *c, const float e[3], float *x, float *y)
{
    float sx = e[0], sy = e[1];
    if (!c->cam.ortho) {
        sx /= -e[2];
        sy /= -e[2];
    }
    *x = 0.5f * (float)c->cam.width + sx * c->px_per_unit;
    *y = 0.5f * (float)c->cam.height + sy * c->px_per_unit;
}

/* ---------------------------------------------------------------- rectangles */

/* Which side of the clip planes a ball lies wholly on: -1 nearer than the near plane, 1
 * beyond the far plane, 0 neither. */
static int ball_side(const ms_glcull *c, const float e[3], float r)
{
    float d = -e[2];
    return d + r < c->cam.near ? -1 : d - r > c->cam.far ? 1 : 0;
}

/* Window rectangle (GL pixels) of a ball, and its nearest distance: 1, or 2 when it crosses
 * the eye plane (its projection is unbounded: keep what it bounds). Under perspective the
 * bounds are the slopes of the planes through the eye that touch the ball (as the vertex
 * shader computes them). */
static int ball_rect(const ms_glcull *c, const float e[3], float r, float rect[4], float *near)
{
    float d = -e[2];
    if (c->cam.ortho) {
        float x, y, rp = r * c->px_per_unit;
        to_window(c, e, &x, &y);
        rect[0] = x - rp; rect[1] = y - rp; rect[2] = x + rp; rect[3] = y + rp;
        *near = d - r;
        return 1;
    }
    if (d <= r * 1.0001f) return 2;
    float k = d * d - r * r, w = 0.5f * (float)c->cam.width, h = 0.5f * (float)c->cam.height;
    for (int a = 0; a < 2; a++) {
        float s = r * sqrtf(e[a] * e[a] + k), ctr = a ? h : w;
        rect[a] = ctr + (e[a] * d - s) / k * c->px_per_unit;
        rect[a + 2] = ctr + (e[a] * d + s) / k * c->px_per_unit;
    }
    *near = sqrtf(e[0] * e[0] + e[1] * e[1] + d * d) - r;
    return 1;
}

/* A window coordinate clamped to [-1, limit + 1] before it becomes an int (NaN: -1). */
static int to_pixel(float v, int limit)
{
    return v >= -1.0f ? (int)fminf(v, (float)limit + 1.0f) : -1;
}

/* The pixel centres inside a rectangle widened by eps, clipped to the image; 0 if none. */
static int rect_pixels(const ms_glcull *c, const float rect[4], float eps, int px[4])
{
    px[0] = MS_MAX(0, to_pixel(ceilf(rect[0] - eps - 0.5f), c->cam.width));
    px[1] = MS_MAX(0, to_pixel(ceilf(rect[1] - eps - 0.5f), c->cam.height));
    px[2] = MS_MIN(c->cam.width - 1, to_pixel(floorf(rect[2] + eps - 0.5f), c->cam.width));
    px[3] = MS_MIN(c->cam.height - 1, to_pixel(floorf(rect[3] + eps - 0.5f), c->cam.height));
    return px[0] <= px[2] && px[1] <= px[3];
}

/* ---------------------------------------------------------------- occluders */

static void store_min(_Atomic uint32_t *cell, float v)
{
    /* Non-negative floats order as their bit patterns. */
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    if (atomic_load_explicit(cell, memory_order_relaxed) > bits)
        atomic_store_explicit(cell, bits, memory_order_relaxed);
}

/* Every pixel whose ray meets an opaque ball (eye space) well inside its rim receives the
 * distance of the hit, nudged farther. Double precision: the rim of a ball a thousandth of
 * the eye distance across must not move. */
static void splat_ball(ms_glcull *c, const float e[3], float r)
{
    float rect[4], near;
    int px[4];
    if (r <= 0 || -e[2] - r < c->cam.near || -e[2] + r > c->cam.far ||
        ball_rect(c, e, r, rect, &near) != 1 || !rect_pixels(c, rect, 0.0f, px))
        return;
    double cx = e[0], cy = e[1], cz = e[2];
    double dist = sqrt(cx * cx + cy * cy + cz * cz), rin = r * 0.999 - 1e-6 * dist;
    if (rin <= 0) return;
    double r2 = rin * rin;
    double sx = 2.0 * c->cam.hx / c->cam.width, sy = 2.0 * c->cam.hy / c->cam.height;
    for (int y = px[1]; y <= px[3]; y++) {
        double ry = (y + 0.5) * sy - c->cam.hy;
        _Atomic uint32_t *row = c->occ + (size_t)y * (size_t)c->cam.width;
        for (int x = px[0]; x <= px[2]; x++) {
            double rx = (x + 0.5) * sx - c->cam.hx, d[3] = {0, 0, -1}, o[3] = {0, 0, 0};
            if (c->cam.ortho) {
                o[0] = rx;
                o[1] = ry;
            } else {
                double il = 1.0 / sqrt(rx * rx + ry * ry + 1.0);
                d[0] = rx * il; d[1] = ry * il; d[2] = -il;
            }
            double t0 = (cx - o[0]) * d[0] + (cy - o[1]) * d[1] + (cz - o[2]) * d[2];
            double mx = o[0] + t0 * d[0] - cx, my = o[1] + t0 * d[1] - cy, mz = t0 * d[2] - cz;
            double m2 = mx * mx + my * my + mz * mz;
            if (m2 < r2) store_min(row + x, (float)((t0 - sqrt(r2 - m2)) * 1.00001 + 1e-6));
        }
    }
}

typedef struct occ_job {
    ms_glcull *c;
    const ms_displaylist *dl;
    const float *mv;
    float rscale;
} occ_job;

static void occ_spheres(void *ctx, size_t b, size_t e, int t)
{
    occ_job *j = ctx;
    const ms_dl_spheres *s = &j->dl->spheres;
    for (size_t i = b; i < e; i++) {
        if (s->color[i].a < 255) continue;
        float p[3];
        xform(j->mv, s->xyz + 3 * i, p);
        splat_ball(j->c, p, s->radius[i] * j->rscale);
    }
}

/* Balls of the cylinder's radius centred on its axis, at least a radius from each end, a
 * radius apart (at most 8). */
static void occ_cylinders(void *ctx, size_t b, size_t e, int t)
{
    occ_job *j = ctx;
    const ms_dl_cylinders *s = &j->dl->cylinders;
    for (size_t i = b; i < e; i++) {
        if (s->color[i].a < 255) continue;
        float a[3], z[3], r = s->radius[i] * j->rscale;
        xform(j->mv, s->base + 3 * i, a);
        xform(j->mv, s->apex + 3 * i, z);
        float len = sqrtf((z[0] - a[0]) * (z[0] - a[0]) + (z[1] - a[1]) * (z[1] - a[1]) +
                          (z[2] - a[2]) * (z[2] - a[2]));
        if (len < 2 * r || r <= 0) continue;
        int n = MS_MIN(8, (int)((len - 2 * r) / r) + 1);
        for (int k = 0; k < n; k++) {
            float f = n == 1 ? 0.5f : (r + (len - 2 * r) * (float)k / (float)(n - 1)) / len, p[3];
            for (int d = 0; d < 3; d++) p[d] = a[d] + f * (z[d] - a[d]);
            splat_ball(j->c, p, r);
        }
    }
}

void ms_glcull_occluders(ms_glcull *c, const ms_displaylist *dl, const float mv[16], float rscale)
{
    occ_job j = {c, dl, mv, rscale};
    ms_parallel_for(dl->spheres.n, CHUNK, occ_spheres, &j);
    ms_parallel_for(dl->cylinders.n, CHUNK, occ_cylinders, &j);
}

/* ---------------------------------------------------------------- tests */

/* The eye ray of a pixel centre (double: o origin, d unit direction). */
static void pixel_ray(const ms_glcull *c, int x, int y, double o[3], double d[3])
{
    double rx = (x + 0.5) * 2.0 * c->cam.hx / c->cam.width - c->cam.hx;
    double ry = (y + 0.5) * 2.0 * c->cam.hy / c->cam.height - c->cam.hy;
    o[0] = o[1] = o[2] = 0;
    d[0] = d[1] = 0;
    d[2] = -1;
    if (c->cam.ortho) {
        o[0] = rx;
        o[1] = ry;
        return;
    }
    double il = 1.0 / sqrt(rx * rx + ry * ry + 1.0);
    d[0] = rx * il;
    d[1] = ry * il;
    d[2] = -il;
}

/* A primitive inside the capsule of radius r around segment a-b (a ball when a == b). */
typedef struct capsule {
    const float *a, *b;
    double r;
} capsule;

/* Whether the ray may meet the capsule, and then a distance along it no farther than the
 * first hit: exact for a ball; for a segment, the nearer end's distance less the radius.
 * The radius is widened against rounding. */
static int capsule_hit(const capsule *k, const double o[3], const double d[3], double *t)
{
    double u[3], w[3], uu = 0, ud = 0, wd = 0, wu = 0;
    for (int i = 0; i < 3; i++) {
        u[i] = (double)k->b[i] - k->a[i];
        w[i] = (double)k->a[i] - o[i];
        uu += u[i] * u[i]; ud += u[i] * d[i]; wd += w[i] * d[i]; wu += w[i] * u[i];
    }
    /* the segment point nearest the ray's line: s minimises |w + s u - ((w + s u).d) d| */
    double den = uu - ud * ud, s = den > 1e-300 ? (wd * ud - wu) / den : 0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double q[3], qd = 0, m2 = 0;
    for (int i = 0; i < 3; i++) q[i] = w[i] + s * u[i];
    for (int i = 0; i < 3; i++) qd += q[i] * d[i];
    for (int i = 0; i < 3; i++) m2 += (q[i] - qd * d[i]) * (q[i] - qd * d[i]);
    double dist = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double r = k->r * 1.001 + 1e-6 * dist;
    if (m2 > r * r) return 0;
    *t = uu > 0 ? fmin(wd, wd + ud) - r : qd - sqrt(r * r - m2);
    *t = *t * (1.0 - 1e-5) - 1e-6;
    return 1;
}

/* Whether any pixel centre of the rectangle may show the primitive: its ray meets the
 * capsule no farther than the occlusion buffer (checked first against near, the least
 * distance of the whole primitive). */
static int rect_visible(const ms_glcull *c, const float rect[4], float near, const capsule *k)
{
    int px[4];
    if (!rect_pixels(c, rect, RECT_MARGIN + 0.02f, px)) return 0;
    if (near < 0 || (size_t)(px[2] - px[0] + 1) * (size_t)(px[3] - px[1] + 1) > TEST_MAX_PIXELS)
        return 1;
    uint32_t bits;
    memcpy(&bits, &near, sizeof bits);
    for (int y = px[1]; y <= px[3]; y++) {
        const _Atomic uint32_t *row = c->occ + (size_t)y * (size_t)c->cam.width;
        for (int x = px[0]; x <= px[2]; x++) {
            uint32_t ob = atomic_load_explicit(row + x, memory_order_relaxed);
            if (ob < bits) continue;
            double o[3], d[3], t;
            float occ;
            memcpy(&occ, &ob, sizeof occ);
            pixel_ray(c, x, y, o, d);
            if (capsule_hit(k, o, d, &t) && t <= occ) return 1;
        }
    }
    return 0;
}

/* A primitive bounded by two balls (the same one twice for a sphere): gone when both lie
 * on the same far side of a clip plane, else tested over the union of their rectangles (as
 * the vertex shader bounds it). */
static int two_balls_visible(const ms_glcull *c, const float a[3], float ra, const float b[3],
                             float rb)
{
    float r1[4], r2[4], n1 = 0, n2 = 0;
    int side = ball_side(c, a, ra);
    if (side && side == ball_side(c, b, rb)) return 0;
    if (ball_rect(c, a, ra, r1, &n1) == 2 || (a != b && ball_rect(c, b, rb, r2, &n2) == 2))
        return 1;
    if (a != b) {
        r1[0] = MS_MIN(r1[0], r2[0]); r1[1] = MS_MIN(r1[1], r2[1]);
        r1[2] = MS_MAX(r1[2], r2[2]); r1[3] = MS_MAX(r1[3], r2[3]);
        n1 = MS_MIN(n1, n2);
    }
    capsule k = {a, b, MS_MAX(ra, rb)};
    return rect_visible(c, r1, n1, &k);
}

typedef struct test_job {
    const ms_glcull *c;
    const ms_displaylist *dl;
    int kind;
    const float *mv;
    float rscale;
    ms_glcull_sel *sel;
} test_job;

static int primitive_visible(const test_job *j, size_t i)
{
    const ms_displaylist *dl = j->dl;
    float a[3], b[3];
    if (j->kind == MS_DL_SPHERES) {
        xform(j->mv, dl->spheres.xyz + 3 * i, a);
        return two_balls_visible(j->c, a, dl->spheres.radius[i] * j->rscale, a, 0);
    }
    if (j->kind == MS_DL_CYLINDERS) {
        float r = dl->cylinders.radius[i] * j->rscale;
        xform(j->mv, dl->cylinders.base + 3 * i, a);
        xform(j->mv, dl->cylinders.apex + 3 * i, b);
        return two_balls_visible(j->c, a, r, b, r);
    }
    xform(j->mv, dl->cones.base + 3 * i, a);
    xform(j->mv, dl->cones.apex + 3 * i, b);
    return two_balls_visible(j->c, a, dl->cones.rbase[i] * j->rscale, b,
                             dl->cones.rapex[i] * j->rscale);
}

static void test_chunk(void *ctx, size_t b, size_t e, int t)
{
    test_job *j = ctx;
    for (size_t ch = b; ch < e; ch++) {
        size_t i0 = ch * CHUNK, i1 = MS_MIN(j->sel->n, i0 + CHUNK), kept = 0;
        for (size_t i = i0; i < i1; i++) kept += j->sel->keep[i] = (uint8_t)primitive_visible(j, i);
        j->sel->offset[ch] = kept;
    }
}

int ms_glcull_test(const ms_glcull *c, const ms_displaylist *dl, int kind, const float mv[16],
                   float rscale, ms_glcull_sel *sel, ms_error *err)
{
    size_t n = kind == MS_DL_SPHERES ? dl->spheres.n : kind == MS_DL_CYLINDERS ? dl->cylinders.n
                                                                               : dl->cones.n;
    size_t nch = (n + CHUNK - 1) / CHUNK;
    memset(sel, 0, sizeof *sel);
    sel->n = n;
    sel->keep = malloc(n ? n : 1);
    sel->offset = malloc((nch + 1) * sizeof *sel->offset);
    if (!sel->keep || !sel->offset) {
        ms_glcull_sel_free(sel);
        ms_error_set(err, "out of memory");
        return -1;
    }
    test_job j = {c, dl, kind, mv, rscale, sel};
    ms_parallel_for(nch, 1, test_chunk, &j);
    size_t acc = 0;
    for (size_t ch = 0; ch < nch; ch++) {
        size_t k = sel->offset[ch];
        sel->offset[ch] = acc;
        acc += k;
    }
    sel->offset[nch] = acc;
    sel->kept = acc;
    return 0;
}

void ms_glcull_sel_free(ms_glcull_sel *sel)
{
    free(sel->keep);
    free(sel->offset);
    memset(sel, 0, sizeof *sel);
}

/* ---------------------------------------------------------------- compaction */

typedef struct gather_job {
    const ms_glcull_sel *sel;
    const uint8_t *src;
    uint8_t *dst;
    size_t elsize;
} gather_job;

static void gather_chunk(void *ctx, size_t b, size_t e, int t)
{
    gather_job *g = ctx;
    for (size_t ch = b; ch < e; ch++) {
        size_t i0 = ch * CHUNK, i1 = MS_MIN(g->sel->n, i0 + CHUNK);
        uint8_t *out = g->dst + g->sel->offset[ch] * g->elsize;
        for (size_t i = i0; i < i1; i++) {
            if (!g->sel->keep[i]) continue;
            memcpy(out, g->src + i * g->elsize, g->elsize);
            out += g->elsize;
        }
    }
}

void *ms_glcull_gather(const ms_glcull_sel *sel, const void *src, size_t elsize)
{
    uint8_t *dst = ms_alloc_array(sel->kept ? sel->kept : 1, elsize);
    if (!dst) return NULL;
    gather_job g = {sel, src, dst, elsize};
    ms_parallel_for((sel->n + CHUNK - 1) / CHUNK, 1, gather_chunk, &g);
    return dst;
}
