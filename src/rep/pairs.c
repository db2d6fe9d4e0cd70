/* pairs.c: pairs of selected atoms within a distance, through the cell grid of base/grid.h
 * (linear in the atoms): the bonds of DynamicBonds and of a bond cutoff, the candidates of HBonds.
 * Each atom looks at the 27 cells around its own for partners of higher index; the search
 * runs twice in parallel, counting then filling, so the pairs come out in atom order. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/grid.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cells at least cutoff wide, at most about two per selected atom, computed in single
 * precision (base/grid.h): that fixes the order of the pairs. */
static int grid_build(ms_grid *g, const ms_rep_build *b, float cutoff, ms_error *err)
{
    ms_grid_points p = {b->pos, 3, b->idx, b->nsel};
    ms_grid_spec spec = {cutoff, 2.0, 8.0, 1.26, 1};
    return ms_grid_build(g, &p, &spec, err);
}

typedef struct search {
    const ms_rep_build *b;
    const ms_grid *g;
    float c2;
    ms_rep_pair_fn keep;
    const void *ctx;
    size_t *count;              /* per selected position: pairs, then offsets */
    uint32_t *out;              /* NULL in the counting pass */
} search;

/* Partners j > i of atom at selected position s; writes them when out is set. */
static size_t partners(const search *x, size_t s)
{
    uint32_t i = x->b->idx[s];
    const float *p = ms_rep_xyz(x->b, i);
    ms_grid_run runs[9];
    int nr = ms_grid_near(x->g, p, runs);
    size_t n = 0, o = x->out ? x->count[s] : 0;
    for (int r = 0; r < nr; r++)
        for (uint32_t k = runs[r].begin; k < runs[r].end; k++) {
            uint32_t j = x->g->items[k];
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
    ms_grid g;
    search x = {b, &g, cutoff * cutoff, keep, ctx, NULL, NULL};
    int rc = -1;
    if (grid_build(&g, b, cutoff, err)) return -1;
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
    ms_grid_free(&g);
    return rc;
}
