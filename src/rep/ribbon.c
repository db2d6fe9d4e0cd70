/* ribbon.c: the extrusion NewRibbons and NewCartoon draw: a cubic spline through each
 * chain's control points carrying an elliptical cross-section (half width along the guide
 * vector, half height across it), as VMD's draw_spline_new does. Each selected residue owns
 * the piece of the chain from the midpoint before its control point to the midpoint after,
 * in its control atom's colour, so colours change crisply at residue boundaries. Pieces are
 * independent: their vertex blocks come from prefix sums and are filled in parallel. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>
#include <string.h>

#define MAX_PANELS 256

typedef struct ribbon_job {
    const ms_rep_build *b;
    const ms_rep_ribbon *r;
    const uint32_t *chain;      /* chain of each backbone residue */
    size_t *pfirst, *sfirst;    /* per residue: first ring, first section (0 when not drawn) */
    ms_dl_mesh *mesh;
    size_t v0, t0;
    int panels, divs;
    float basis[4][4];
    float sn[MAX_PANELS], cs[MAX_PANELS];
} ribbon_job;

int ms_rep_ribbon_divs(float res)
{
    int d = 2 * (int)((res + 2.0f) / 6.0f + 0.5f);
    return d < 2 ? 2 : d > 64 ? 64 : d;
}

/* Rings of residue r's piece: 0 when it is not drawn. */
static size_t rings_of(const ribbon_job *j, size_t r)
{
    const ms_rep_chain *ch = &j->r->bb->chains[j->chain[r]];
    size_t q = r - ch->first;
    if (ch->n < 2 || !ms_rep_on(j->b, j->r->bb->atom[r])) return 0;
    return (q > 0 ? (size_t)j->divs / 2 + 1 : 1) + (q + 1 < ch->n ? (size_t)j->divs / 2 : 0);
}

static void count_rings(void *ctxp, size_t begin, size_t end, int thread)
{
    ribbon_job *j = ctxp;
    for (size_t r = begin; r < end; r++) {
        size_t n = rings_of(j, r);
        j->pfirst[r] = n;
        j->sfirst[r] = n ? n - 1 : 0;
    }
}

static float lerp(float a, float b, float t) { return a + (b - a) * t; }

/* One cross-section: point on segment s (control points s-1 to s of the chain) at t. */
typedef struct ring_in {
    size_t s;                   /* segment, chain-relative, 1..n-1 */
    float t;
    float w, h;                 /* half width and half height */
    float perp[3];
} ring_in;

/* A segment's cubic: point(t) = ((q0 t + q1) t + q2) t + q3; chord for standing points. */
typedef struct segment {
    size_t s;
    float q[4][3], chord[3];
} segment;

static void segment_of(const ribbon_job *j, const ms_rep_chain *ch, size_t s, segment *g)
{
    const float *cp = j->r->cp;
    long n = (long)ch->n;
    const float *p[4];
    for (int k = 0; k < 4; k++) {
        long c = (long)s - 2 + k;
        c = c < 0 ? 0 : c >= n ? n - 1 : c;
        p[k] = cp + 3 * (ch->first + (size_t)c);
    }
    for (int m = 0; m < 4; m++)
        for (int k = 0; k < 3; k++)
            g->q[m][k] = j->basis[m][0] * p[0][k] + j->basis[m][1] * p[1][k] +
                         j->basis[m][2] * p[2][k] + j->basis[m][3] * p[3][k];
    for (int k = 0; k < 3; k++) g->chord[k] = p[2][k] - p[1][k];
    g->s = s;
}

/* Point and unit tangent at t. */
static void segment_at(const segment *g, float t, float pos[3], float tan[3])
{
    for (int k = 0; k < 3; k++) {
        pos[k] = ((g->q[0][k] * t + g->q[1][k]) * t + g->q[2][k]) * t + g->q[3][k];
        tan[k] = (3 * g->q[0][k] * t + 2 * g->q[1][k]) * t + g->q[2][k];
    }
    float l = sqrtf(tan[0] * tan[0] + tan[1] * tan[1] + tan[2] * tan[2]);
    if (!(l > 1e-12f)) {   /* a standing point: use the chord */
        for (int k = 0; k < 3; k++) tan[k] = g->chord[k];
        l = sqrtf(tan[0] * tan[0] + tan[1] * tan[1] + tan[2] * tan[2]);
        if (!(l > 1e-12f)) {
            tan[0] = 1;
            tan[1] = tan[2] = 0;
            l = 1;
        }
    }
    for (int k = 0; k < 3; k++) tan[k] /= l;
}

/* e1: the guide made perpendicular to the tangent; e2 = e1 x T. */
static void frame(const float *tan, const float *perp, float e1[3], float e2[3])
{
    float d = perp[0] * tan[0] + perp[1] * tan[1] + perp[2] * tan[2];
    for (int k = 0; k < 3; k++) e1[k] = perp[k] - d * tan[k];
    float l = sqrtf(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    if (!(l > 1e-6f)) {   /* no usable guide: any perpendicular */
        float a[3] = {fabsf(tan[0]) < 0.9f ? 1.0f : 0.0f, fabsf(tan[0]) < 0.9f ? 0.0f : 1.0f, 0};
        d = a[0] * tan[0] + a[1] * tan[1];
        for (int k = 0; k < 3; k++) e1[k] = a[k] - d * tan[k];
        l = sqrtf(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    }
    for (int k = 0; k < 3; k++) e1[k] /= l;
    e2[0] = e1[1] * tan[2] - e1[2] * tan[1];
    e2[1] = e1[2] * tan[0] - e1[0] * tan[2];
    e2[2] = e1[0] * tan[1] - e1[1] * tan[0];
}

/* The cross-section's vertex offsets and normals in the (e1, e2) frame, for one w and h;
 * kept while consecutive rings share them. */
typedef struct shape {
    float w, h;
    float a[MAX_PANELS], b[MAX_PANELS], nx[MAX_PANELS], ny[MAX_PANELS];
} shape;

static void shape_set(shape *sh, const ribbon_job *j, float w, float h)
{
    w = w > 1e-6f ? w : 1e-6f;
    h = h > 1e-6f ? h : 1e-6f;
    if (w == sh->w && h == sh->h) return;
    sh->w = w;
    sh->h = h;
    for (int p = 0; p < j->panels; p++) {
        float s = j->sn[p], c = j->cs[p], nx = s / w, ny = c / h;
        float nl = 1.0f / sqrtf(nx * nx + ny * ny);
        sh->a[p] = w * s;
        sh->b[p] = h * c;
        sh->nx[p] = nx * nl;
        sh->ny[p] = ny * nl;
    }
}

/* ms_normal_quantize for a component of a unit vector (no clamping needed), rounding to
 * nearest with one instruction. */
static inline int8_t quantize(float f)
{
    return (int8_t)lrintf(f * 127.5f - 0.5f);
}

static void emit_ring(const ribbon_job *j, const segment *g, const ring_in *in, shape *sh,
                      ms_rgba8 col, size_t v)
{
    float pos[3], tan[3], e1[3], e2[3];
    segment_at(g, in->t, pos, tan);
    frame(tan, in->perp, e1, e2);
    if (!isfinite(pos[0] + pos[1] + pos[2] + e1[0] + e1[1] + e1[2] + e2[0] + e2[1] + e2[2]))
        for (int k = 0; k < 3; k++) pos[k] = e1[k] = e2[k] = 0;   /* bad coordinates */
    shape_set(sh, j, in->w, in->h);
    ms_dl_mesh *m = j->mesh;
    float *xyz = m->xyz + 3 * v;
    int8_t *nrm = m->normal + 3 * v;
    for (int p = 0; p < j->panels; p++) {
        float a = sh->a[p], b = sh->b[p], nx = sh->nx[p], ny = sh->ny[p];
        for (int k = 0; k < 3; k++) {
            xyz[3 * p + k] = pos[k] + a * e1[k] + b * e2[k];
            nrm[3 * p + k] = quantize(nx * e1[k] + ny * e2[k]);
        }
        m->color[v + (size_t)p] = col;
    }
}

/* The cross-section of residue q's piece on segment s at t (s == q: the half before the
 * control point, s == q + 1: the half after), with VMD's width rules for sheet arrows. */
static void ring_params(const ribbon_job *j, const ms_rep_chain *ch, size_t q, size_t s,
                        float t, ring_in *in)
{
    const ms_rep_ribbon *r = j->r;
    size_t base = ch->first, last = ch->n - 1;
    size_t a = s - 1, b = s;   /* the segment's control points */
    size_t next = q < last ? q + 1 : q;
    float wq = r->w[base + q];
    in->s = s;
    in->t = t;
    if (wq < 0) {   /* arrowhead: tapers over the whole piece to the next width */
        float u = s == q ? t - 0.5f : t + 0.5f;
        in->w = lerp(-wq, fabsf(r->w[base + next]), u);
    } else if (s == q) {
        float wp = r->w[base + a];
        in->w = wp < 0 ? wq : lerp(wp, wq, t);
    } else {
        float wn = r->w[base + b];
        in->w = wn < 0 ? wq : lerp(wq, wn, t);
    }
    in->h = lerp(r->h[base + a], r->h[base + b], t);
    for (int k = 0; k < 3; k++)
        in->perp[k] = lerp(r->perp[3 * (base + a) + k], r->perp[3 * (base + b) + k], t);
}

static void fill_pieces(void *ctxp, size_t begin, size_t end, int thread)
{
    const ribbon_job *j = ctxp;
    const ms_rep_backbone *bb = j->r->bb;
    int half = j->divs / 2, P = j->panels;
    shape sh;
    sh.w = sh.h = -1;
    for (size_t r = begin; r < end; r++) {
        size_t nrings = rings_of(j, r);
        if (!nrings) continue;
        const ms_rep_chain *ch = &bb->chains[j->chain[r]];
        size_t q = r - ch->first, v = j->v0 + j->pfirst[r] * (size_t)P, k = 0;
        ms_rgba8 col = ms_rep_rgba(j->b, bb->atom[r]);
        ring_in in;
        segment g;
        if (q > 0) {
            segment_of(j, ch, q, &g);
            for (int i = half; i <= j->divs; i++, k++) {
                ring_params(j, ch, q, q, (float)i / (float)j->divs, &in);
                emit_ring(j, &g, &in, &sh, col, v + k * (size_t)P);
            }
        }
        if (q + 1 < ch->n) {
            segment_of(j, ch, q + 1, &g);
            for (int i = q > 0 ? 1 : 0; i <= half; i++, k++) {
                ring_params(j, ch, q, q + 1, (float)i / (float)j->divs, &in);
                emit_ring(j, &g, &in, &sh, col, v + k * (size_t)P);
            }
        }
        uint32_t *tri = j->mesh->tri + 3 * (j->t0 + 2 * j->sfirst[r] * (size_t)P);
        for (size_t ring = 0; ring + 1 < nrings; ring++) {
            uint32_t base = (uint32_t)(v + ring * (size_t)P);
            for (int p = 0; p < P; p++) {
                uint32_t a = base + (uint32_t)p, bq = base + (uint32_t)(p + 1 < P ? p + 1 : 0);
                uint32_t c = a + (uint32_t)P, d = bq + (uint32_t)P;
                tri[0] = a; tri[1] = bq; tri[2] = c;     /* counter-clockwise from outside */
                tri[3] = bq; tri[4] = d; tri[5] = c;
                tri += 6;
            }
        }
    }
}

int ms_rep_ribbon_build(const ms_rep_build *b, const ms_rep_ribbon *r, ms_displaylist *dl,
                        ms_error *err)
{
    const ms_rep_backbone *bb = r->bb;
    if (bb->n == 0) return 0;
    ribbon_job j;
    memset(&j, 0, sizeof j);
    j.b = b;
    j.r = r;
    j.panels = r->panels < 3 ? 3 : r->panels > MAX_PANELS ? MAX_PANELS : r->panels;
    j.divs = r->divs;
    ms_rep_spline_basis(j.basis, r->bspline);
    for (int p = 0; p < j.panels; p++) {
        double a = 2.0 * 3.14159265358979323846 * p / j.panels;
        j.sn[p] = (float)sin(a);
        j.cs[p] = (float)cos(a);
    }
    uint32_t *chain = ms_rep_scratch_get(b->scratch, MS_SCR_CHAIN, bb->n * sizeof *chain, err);
    j.pfirst = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (bb->n + 1) * sizeof(size_t), err);
    j.sfirst = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA, (bb->n + 1) * sizeof(size_t), err);
    if (!chain || !j.pfirst || !j.sfirst) return -1;
    for (size_t c = 0; c < bb->nchains; c++)
        for (size_t q = 0; q < bb->chains[c].n; q++) chain[bb->chains[c].first + q] = (uint32_t)c;
    j.chain = chain;
    ms_parallel_for(bb->n, 1024, count_rings, &j);
    size_t rings = ms_rep_scan(j.pfirst, bb->n), sections = ms_rep_scan(j.sfirst, bb->n);
    if (rings == 0) return 0;
    size_t nv, nt;
    if (ms_mul_size(rings, (size_t)j.panels, &nv) || ms_mul_size(sections, 2 * (size_t)j.panels, &nt)) {
        ms_error_set(err, "ribbon too large");
        return -1;
    }
    if (ms_dl_mesh_extend(dl, nv, nt, &j.v0, &j.t0, err)) return -1;
    j.mesh = &dl->mesh;
    ms_parallel_for(bb->n, 256, fill_pieces, &j);
    return 0;
}

int ms_rep_ribbon_method(const ms_rep_build *b, ms_rep_ribbon_fill fill, ms_displaylist *dl,
                         ms_error *err)
{
    ms_rep_backbone bb;
    memset(&bb, 0, sizeof bb);
    if (ms_rep_backbone_build(b->m, &bb, err)) return -1;
    int rc = -1;
    float *geo = ms_rep_scratch_get(b->scratch, MS_SCR_PATH, (bb.n + 1) * 8 * sizeof(float), err);
    if (!geo) goto done;
    float *cp = geo, *perp = geo + 3 * bb.n, *w = geo + 6 * bb.n, *h = geo + 7 * bb.n;
    fill(b, &bb, cp, perp, w, h);
    ms_rep_ribbon rib = {&bb, cp, perp, w, h, b->p[3] != 0, ms_rep_res(b->p[1]),
                         ms_rep_ribbon_divs(b->p[1])};
    rc = ms_rep_ribbon_build(b, &rib, dl, err);
done:
    ms_rep_backbone_free(&bb);
    return rc;
}
