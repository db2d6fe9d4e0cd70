/* beads.c: VMD's Beads method (radius scale, resolution): a sphere per residue with selected
 * atoms, at their centroid, of radius scale * (largest atom distance from it + 1), in the
 * colour of the residue's last selected atom. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>

typedef struct bead_job {
    const ms_rep_build *b;
    size_t *first;              /* per residue: 1 when drawn, then its sphere */
    ms_dl_spheres *sp;
    size_t s0;
    float scale;
    uint16_t res;
} bead_job;

static void count(void *ctxp, size_t begin, size_t end, int thread)
{
    const bead_job *j = ctxp;
    const ms_molecule *m = j->b->m;
    for (size_t r = begin; r < end; r++) {
        size_t on = 0;
        for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1] && !on; i++)
            on = (size_t)ms_rep_on(j->b, i);
        j->first[r] = on;
    }
}

static void fill(void *ctxp, size_t begin, size_t end, int thread)
{
    const bead_job *j = ctxp;
    const ms_rep_build *b = j->b;
    const ms_molecule *m = b->m;
    for (size_t r = begin; r < end; r++) {
        if (j->first[r + 1] == j->first[r]) continue;
        double c[3] = {0, 0, 0};
        size_t n = 0;
        uint32_t last = 0;
        for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++) {
            if (!ms_rep_on(b, i)) continue;
            for (int k = 0; k < 3; k++) c[k] += ms_rep_xyz(b, i)[k];
            n++;
            last = i;
        }
        float cf[3] = {(float)(c[0] / (double)n), (float)(c[1] / (double)n), (float)(c[2] / (double)n)};
        float r2 = 0;
        for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++) {
            if (!ms_rep_on(b, i)) continue;
            const float *p = ms_rep_xyz(b, i);
            float d = (p[0] - cf[0]) * (p[0] - cf[0]) + (p[1] - cf[1]) * (p[1] - cf[1]) +
                      (p[2] - cf[2]) * (p[2] - cf[2]);
            if (d > r2) r2 = d;
        }
        size_t o = j->s0 + j->first[r];
        for (int k = 0; k < 3; k++) j->sp->xyz[3 * o + k] = cf[k];
        j->sp->radius[o] = j->scale * (sqrtf(r2) + 1.0f);
        j->sp->color[o] = ms_rep_rgba(b, last);
        j->sp->res[o] = j->res;
    }
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    const ms_molecule *m = b->m;
    if (!m->res_start || m->nresidues == 0 || b->nsel == 0) return 0;
    bead_job j = {b, NULL, NULL, 0, b->p[0], ms_rep_res(b->p[1])};
    j.first = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (m->nresidues + 1) * sizeof(size_t), err);
    if (!j.first) return -1;
    ms_parallel_for(m->nresidues, 4096, count, &j);
    j.first[m->nresidues] = 0;
    size_t n = ms_rep_scan(j.first, m->nresidues + 1);
    long s0 = ms_dl_extend(dl, MS_DL_SPHERES, n, err);
    if (s0 < 0) return -1;
    j.sp = &dl->spheres;
    j.s0 = (size_t)s0;
    ms_parallel_for(m->nresidues, 4096, fill, &j);
    return 0;
}

const ms_rep_method ms_rep_beads = {
    "Beads", 2, {{"sphere scale", 1.0f}, {"sphere resolution", 12.0f}}, 0, build};
