/* grid.c: `within d of S` through the cell grid of base/grid.h. The atoms of S (and, for
 * pbwithin, their periodic images near the candidates) are sorted into cells at least d wide;
 * each candidate atom then looks only at the 27 cells around its own. Building is linear in
 * |S|, the search linear in the candidates, and the candidate loop runs in parallel. */
#include "config.h"
#include "select/selint.h"
#include "base/grid.h"
#include "base/threads.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

typedef struct grid {
    ms_grid cells;           /* the points by cell */
    float *pts;              /* their coordinates in cell order, xyz */
    float reach_lo[3], reach_hi[3];  /* the points' box grown by d: nothing outside is near */
} grid;

/* ---------------------------------------------------------------- gathering S */

typedef struct points {
    float *xyz;
    size_t n, cap;
} points;

static int push(points *p, float x, float y, float z)
{
    if (!isfinite(x) || !isfinite(y) || !isfinite(z)) return 0;
    if (ms_grow((void **)&p->xyz, &p->cap, 3 * (p->n + 1), sizeof *p->xyz)) return -1;
    p->xyz[3 * p->n] = x;
    p->xyz[3 * p->n + 1] = y;
    p->xyz[3 * p->n + 2] = z;
    p->n++;
    return 0;
}

/* Bounding box of the candidates' coordinates, grown by d. */
static void candidate_box(const ms_selctx *c, const ms_bitset *cand, double d, float lo[3],
                          float hi[3])
{
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t w = 0; w < ms_bitset_nwords(cand); w++)
        for (uint64_t m = cand->words[w]; m; m &= m - 1) {
            const float *p = c->pos + 3 * (w * 64 + (size_t)__builtin_ctzll(m));
            for (int k = 0; k < 3; k++) {
                if (p[k] < lo[k]) lo[k] = p[k];
                if (p[k] > hi[k]) hi[k] = p[k];
            }
        }
    for (int k = 0; k < 3; k++) lo[k] -= (float)d, hi[k] += (float)d;
}

/* The points of S; with periodic set, also their images in the 26 neighbouring cells that
 * fall near a candidate. */
static int gather(const ms_selctx *c, const ms_bitset *cand, const ms_bitset *src, double d,
                  int periodic, points *pts)
{
    double v[3][3] = {{0}};   /* zero unless periodic: 0 * garbage could be NaN */
    float lo[3], hi[3];
    int images = periodic && c->cell && ms_cell_vectors(c->cell, v);
    if (images) candidate_box(c, cand, d, lo, hi);
    for (size_t w = 0; w < ms_bitset_nwords(src); w++)
        for (uint64_t m = src->words[w]; m; m &= m - 1) {
            const float *p = c->pos + 3 * (w * 64 + (size_t)__builtin_ctzll(m));
            for (int i = images ? -1 : 0; i <= (images ? 1 : 0); i++)
                for (int j = images ? -1 : 0; j <= (images ? 1 : 0); j++)
                    for (int k = images ? -1 : 0; k <= (images ? 1 : 0); k++) {
                        float q[3];
                        for (int e = 0; e < 3; e++)
                            q[e] = p[e] + (float)(i * v[0][e] + j * v[1][e] + k * v[2][e]);
                        if ((i || j || k) && (q[0] < lo[0] || q[0] > hi[0] || q[1] < lo[1] ||
                                              q[1] > hi[1] || q[2] < lo[2] || q[2] > hi[2]))
                            continue;
                        if (push(pts, q[0], q[1], q[2])) return -1;
                    }
        }
    return 0;
}

/* ---------------------------------------------------------------- the grid */

/* The cell grid of base/grid.h over the points (cells at least d wide, a few per point),
 * their coordinates copied in cell order, and the box of the points grown by d. */
static int grid_build(grid *g, const points *p, double d, ms_error *err)
{
    ms_grid_points gp = {p->xyz, 3, NULL, p->n};
    /* a hair wider than d, so rounding never puts two points d apart two cells apart */
    ms_grid_spec spec = {MS_MAX(d * 1.000001, 1e-3), 8.0, 4096.0, 1.26, 0};
    if (ms_grid_build(&g->cells, &gp, &spec, err)) return -1;
    g->pts = ms_alloc_array(3 * p->n, sizeof *g->pts);
    if (!g->pts) return -1;
    for (size_t k = 0; k < p->n; k++)
        memcpy(g->pts + 3 * k, p->xyz + 3 * (size_t)g->cells.items[k], 3 * sizeof(float));
    const double *lo = g->cells.origin, *hi = g->cells.top;
    for (int k = 0; k < 3; k++) {
        /* generous by 1e-3 relative: the exact test is the distance, this only skips */
        double pad = d + 1e-3 * (fabs(lo[k]) + fabs(hi[k]) + d) + 1e-3;
        g->reach_lo[k] = (float)(lo[k] - pad);
        g->reach_hi[k] = (float)(hi[k] + pad);
    }
    return 0;
}

/* The candidates among atoms [i0, i0+n) (n <= 64) that lie in the points' box grown by d:
 * a branch-free pass that rejects most atoms of a large molecule at once. */
static uint64_t in_reach(const grid *g, const float *pos, size_t i0, size_t n)
{
    uint64_t in = 0;
    const float *p = pos + 3 * i0;
    float xlo = g->reach_lo[0], xhi = g->reach_hi[0];
    for (size_t b = 0; b < n; b++)     /* x first: it alone rejects most atoms */
        in |= (uint64_t)((p[3 * b] >= xlo) & (p[3 * b] <= xhi)) << b;
    for (uint64_t m = in; m; m &= m - 1) {
        const float *q = p + 3 * (size_t)__builtin_ctzll(m);
        if (!(q[1] >= g->reach_lo[1] && q[1] <= g->reach_hi[1] && q[2] >= g->reach_lo[2] &&
              q[2] <= g->reach_hi[2]))
            in &= ~(m & -m);
    }
    return in;
}

/* Is p within d (d2 = d*d) of a point in the 27 cells around it? */
static int near_point(const grid *g, const float *p, float d2)
{
    long lo[3], hi[3];
    if (!ms_grid_block(&g->cells, p, lo, hi)) return 0;
    for (long z = lo[2]; z <= hi[2]; z++)
        for (long y = lo[1]; y <= hi[1]; y++) {
            /* cells lo..hi of one row are contiguous: one run of points */
            ms_grid_run r = ms_grid_row(&g->cells, lo[0], hi[0], y, z);
            for (const float *q = g->pts + 3 * (size_t)r.begin, *end = g->pts + 3 * (size_t)r.end;
                 q < end; q += 3) {
                float dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
                if (dx * dx + dy * dy + dz * dz <= d2) return 1;
            }
        }
    return 0;
}

/* ---------------------------------------------------------------- the search */

typedef struct search_job {
    const ms_selctx *c;
    const grid *g;
    const ms_bitset *cand, *src;
    ms_bitset *out;
    float d2;
} search_job;

static void search_range(void *ctx, size_t w0, size_t w1, int thread)
{
    search_job *j = ctx;
    size_t n = j->c->n;
    for (size_t w = w0; w < w1; w++) {
        uint64_t cand = j->cand->words[w], bits = cand & j->src->words[w];
        uint64_t rest = cand & ~bits;
        if (rest) rest &= in_reach(j->g, j->c->pos, w * 64, MS_MIN(64, n - w * 64));
        for (; rest; rest &= rest - 1) {
            int b = __builtin_ctzll(rest);
            if (near_point(j->g, j->c->pos + 3 * (w * 64 + (size_t)b), j->d2)) bits |= 1ull << b;
        }
        j->out->words[w] = bits;
    }
}

int ms_sel_within(ms_selctx *c, const ms_bitset *cand, const ms_bitset *src, double cutoff,
                  int periodic, ms_bitset *out)
{
    if (!c->pos) {
        ms_error_set(c->err, "%s: molecule %d has no coordinates", periodic ? "pbwithin" : "within",
                     c->m->id);
        return -1;
    }
    size_t nw = ms_bitset_nwords(out);
    if (!(cutoff > 0)) {   /* within 0 of S is S itself (VMD) */
        for (size_t w = 0; w < nw; w++) out->words[w] = cand->words[w] & src->words[w];
        return 0;
    }
    points pts = {0};
    grid g = {0};
    int rc = -1;
    int gathered = gather(c, cand, src, cutoff, periodic, &pts) == 0;
    if (gathered && pts.n == 0) {
        /* S has no finite coordinates: only its own atoms are within */
        for (size_t w = 0; w < nw; w++) out->words[w] = cand->words[w] & src->words[w];
        rc = 0;
    } else if (gathered && grid_build(&g, &pts, cutoff, c->err) == 0) {
        search_job j = {c, &g, cand, src, out, (float)(cutoff * cutoff)};
        ms_parallel_for(nw, 256, search_range, &j);
        rc = 0;
    } else {
        ms_error_set(c->err, "out of memory in a within search over %zu atoms", pts.n);
    }
    free(pts.xyz);
    ms_grid_free(&g.cells);
    free(g.pts);
    return rc;
}
