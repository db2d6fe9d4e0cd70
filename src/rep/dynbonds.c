/* dynbonds.c: VMD's DynamicBonds method (distance cutoff, bond radius, resolution): a bond
 * between every two selected atoms at most the cutoff apart in the frame drawn (never H-H,
 * never across different alternate locations), as one cylinder whose halves take their
 * atoms' colours. The pairs come from a cell grid, in linear time. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

typedef struct dyn_job {
    const ms_rep_build *b;
    const uint32_t *pairs;
    ms_dl_cylinders *cy;
    size_t c0;
    float radius;
    uint16_t res;
} dyn_job;

static int keep(const void *ctx, uint32_t i, uint32_t j)
{
    return ms_rep_may_bond(ctx, i, j);
}

static void fill(void *ctxp, size_t begin, size_t end, int thread)
{
    const dyn_job *j = ctxp;
    for (size_t k = begin; k < end; k++) {
        uint32_t a = j->pairs[2 * k], b = j->pairs[2 * k + 1];
        const float *pa = ms_rep_xyz(j->b, a), *pb = ms_rep_xyz(j->b, b);
        size_t c = j->c0 + k;
        for (int d = 0; d < 3; d++) {
            j->cy->base[3 * c + d] = pa[d];
            j->cy->joint[3 * c + d] = 0.5f * (pa[d] + pb[d]);
            j->cy->apex[3 * c + d] = pb[d];
        }
        j->cy->color[c] = ms_rep_rgba(j->b, a);
        j->cy->color2[c] = ms_rep_rgba(j->b, b);
        j->cy->radius[c] = j->radius;
        j->cy->flags[c] = MS_CYL_BOND;
        j->cy->res[c] = j->res;
    }
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    if (b->p[0] <= 0.1f || b->nsel == 0) return 0;   /* VMD's guard against huge searches */
    uint32_t *pairs;
    size_t np;
    if (ms_rep_pairs(b, b->p[0], keep, b->m, &pairs, &np, err)) return -1;
    long c0 = ms_dl_extend(dl, MS_DL_CYLINDERS, np, err);
    if (c0 < 0) return -1;
    dyn_job j = {b, pairs, &dl->cylinders, (size_t)c0, b->p[1], ms_rep_res(b->p[2])};
    ms_parallel_for(np, 16384, fill, &j);
    return 0;
}

const ms_rep_method ms_rep_dynamicbonds = {
    "DynamicBonds", 3,
    {{"distance cutoff", 3.0f}, {"bond radius", 0.3f}, {"bond resolution", 12.0f}}, 0, build};
