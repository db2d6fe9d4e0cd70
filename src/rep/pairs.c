/* pairs.c: pairs of selected atoms within a distance, through a uniform cell grid (linear
 * in the atoms): the bonds of DynamicBonds and of a bond cutoff, the candidates of HBonds.
 * Each atom looks at the 27 cells around its own for partners of higher index; the search
 * runs twice in parallel, counting then filling, so the pairs come out in atom order. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct grid {
    float lo[3], cell;
    int dim[3];
    size_t ncells;
    uint32_t *start;            /* ncells + 1 */
    uint32_t *atoms;            /* by cell */
    uint32_t *cellof;           /* per selected position k: its cell, or UINT32_MAX */
} grid;

static size_t cell_index(const grid *g, const float *p, int c[3])
{
    for (int k = 0; k < 3; k++) {
        int v = (int)((p[k] - g->lo[k]) / g->cell);
        c[k] = v < 0 ? 0 : v >= g->dim[k] ? g->dim[k] - 1 : v;
    }
    return ((size_t)c[2] * (size_t)g->dim[1] + (size_t)c[1]) * (size_t)g->dim[0] + (size_t)c[0];
}

static int finite3(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Cells at least cutoff wide, at most about two per atom. */
static int grid_build(grid *g, const ms_rep_build *b, float cutoff)
{
    float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 3; k++) g->lo[k] = INFINITY;
    size_t nfin = 0;
    for (size_t s = 0; s < b->nsel; s++) {
        const float *p = ms_rep_xyz(b, b->idx[s]);
        if (!finite3(p)) continue;
        nfin++;
        for (int k = 0; k < 3; k++) {
            g->lo[k] = fminf(g->lo[k], p[k]);
            hi[k] = fmaxf(hi[k], p[k]);
        }
    }
    if (!nfin) for (int k = 0; k < 3; k++) g->lo[k] = hi[k] = 0;
    double ext[3] = {hi[0] - g->lo[0], hi[1] - g->lo[1], hi[2] - g->lo[2]};
    double cell = cutoff, limit = 2.0 * (double)nfin + 8.0;
    for (;;) {
        double cells = 1;
        for (int k = 0; k < 3; k++) cells *= floor(ext[k] / cell) + 1;
        if (cells <= limit) break;
        cell *= 1.26;
    }
    g->cell = (float)cell;
    g->ncells = 1;
    for (int k = 0; k < 3; k++) {
        g->dim[k] = (int)floor(ext[k] / cell) + 1;
        g->ncells *= (size_t)g->dim[k];
    }
    g->start = calloc(g->ncells + 1, sizeof *g->start);
    g->atoms = ms_alloc_array(nfin ? nfin : 1, sizeof *g->atoms);
    g->cellof = ms_alloc_array(b->nsel ? b->nsel : 1, sizeof *g->cellof);
    if (!g->start || !g->atoms || !g->cellof) return -1;
    int c[3];
    for (size_t s = 0; s < b->nsel; s++) {
        const float *p = ms_rep_xyz(b, b->idx[s]);
        g->cellof[s] = finite3(p) ? (uint32_t)cell_index(g, p, c) : UINT32_MAX;
        if (g->cellof[s] != UINT32_MAX) g->start[g->cellof[s] + 1]++;
    }
    for (size_t i = 0; i < g->ncells; i++) g->start[i + 1] += g->start[i];
    uint32_t *fillp = malloc(g->ncells * sizeof *fillp);
    if (!fillp) return -1;
    memcpy(fillp, g->start, g->ncells * sizeof *fillp);
    for (size_t s = 0; s < b->nsel; s++)   /* ascending atoms within each cell */
        if (g->cellof[s] != UINT32_MAX) g->atoms[fillp[g->cellof[s]]++] = b->idx[s];
    free(fillp);
    return 0;
}

static void grid_free(grid *g)
{
    free(g->start);
    free(g->atoms);
    free(g->cellof);
}

typedef struct search {
    const ms_rep_build *b;
    const grid *g;
    float c2;
    ms_rep_pair_fn keep;
    const void *ctx;
    size_t *count;              /* per selected position: pairs, then offsets */
    uint32_t *out;              /* NULL in the counting pass */
} search;

/* Partners j > i of atom at selected position s; writes them when out is set. */
static size_t partners(const search *x, size_t s)
{
    const grid *g = x->g;
    uint32_t i = x->b->idx[s];
    if (g->cellof[s] == UINT32_MAX) return 0;
    const float *p = ms_rep_xyz(x->b, i);
    int c[3];
    cell_index(g, p, c);
    size_t n = 0, o = x->out ? x->count[s] : 0;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int cx = c[0] + dx, cy = c[1] + dy, cz = c[2] + dz;
                if (cx < 0 || cy < 0 || cz < 0 || cx >= g->dim[0] || cy >= g->dim[1] ||
                    cz >= g->dim[2])
                    continue;
                size_t cell = ((size_t)cz * (size_t)g->dim[1] + (size_t)cy) * (size_t)g->dim[0] + (size_t)cx;
                for (uint32_t k = g->start[cell]; k < g->start[cell + 1]; k++) {
                    uint32_t j = g->atoms[k];
                    if (j <= i) continue;
                    const float *q = ms_rep_xyz(x->b, j);
                    float ddx = q[0] - p[0], ddy = q[1] - p[1], ddz = q[2] - p[2];
                    if (ddx * ddx + ddy * ddy + ddz * ddz > x->c2) continue;
                    if (x->keep && !x->keep(x->ctx, i, j)) continue;
                    if (x->out) {
                        x->out[2 * (o + n)] = i;
                        x->out[2 * (o + n) + 1] = j;
                    }
                    n++;
                }
            }
    return n;
}

static void search_range(void *ctxp, size_t begin, size_t end, int thread)
{
    search *x = ctxp;
    for (size_t s = begin; s < end; s++) {
        size_t n = partners(x, s);
        if (!x->out) x->count[s] = n;
    }
}

int ms_rep_pairs(const ms_rep_build *b, float cutoff, ms_rep_pair_fn keep, const void *ctx,
                 uint32_t **pairs, size_t *npairs, ms_error *err)
{
    *pairs = NULL;
    *npairs = 0;
    if (!(cutoff > 0) || b->nsel == 0) return 0;
    grid g;
    memset(&g, 0, sizeof g);
    search x = {b, &g, cutoff * cutoff, keep, ctx, NULL, NULL};
    int rc = -1;
    if (grid_build(&g, b, cutoff)) {
        ms_error_set(err, "out of memory searching pairs");
        goto done;
    }
    x.count = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (b->nsel + 1) * sizeof(size_t), err);
    if (!x.count) goto done;
    ms_parallel_for(b->nsel, 4096, search_range, &x);
    x.count[b->nsel] = 0;
    size_t total = ms_rep_scan(x.count, b->nsel + 1);
    uint32_t *out = ms_rep_scratch_get(b->scratch, MS_SCR_PAIRS, (2 * total + 2) * sizeof *out, err);
    if (!out) goto done;
    x.out = out;
    ms_parallel_for(b->nsel, 4096, search_range, &x);
    *pairs = out;
    *npairs = total;
    rc = 0;
done:
    grid_free(&g);
    return rc;
}
