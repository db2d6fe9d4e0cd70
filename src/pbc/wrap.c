/* wrap.c: `pbc wrap`: every group (an atom alone, or a compound by its mean position) is
 * moved by the lattice vector that puts it into the cell centred on the wrapping centre:
 * the parallelepiped A B C, or with orthorhombic the brick Ax x By x Cz (z first, then y,
 * then x, which the triangular cell allows). Groups run in parallel, frame after frame;
 * atoms that move alone go by runs of consecutive atoms through the vectorised loops. */
#include "config.h"
#include "base/threads.h"
#include "measure/measure.h"
#include "pbc/internal.h"

#include <math.h>
#include <stdlib.h>

enum { RUN_ATOMS = 8192 };   /* atoms handed to a thread at once */

int ms_pbc_center_of(const ms_molecule *m, size_t f, const ms_pbc_cell *c,
                     const ms_pbc_wrap_opts *o, double center[3], ms_error *err)
{
    ms_atomset s = {m, f, o->centersel, o->ncentersel};
    double lo[3], hi[3];
    switch (o->center) {
    case MS_PBC_CENTER_ORIGIN:
        center[0] = center[1] = center[2] = 0;
        break;
    case MS_PBC_CENTER_COM: {
        double *w = ms_alloc_array(s.n ? s.n : 1, sizeof *w);
        if (!w) { ms_error_set(err, "out of memory"); return -1; }
        for (size_t i = 0; i < s.n; i++) w[i] = m->atoms.mass[s.atoms[i]];
        int rc = ms_measure_center(&s, w, center, err);
        free(w);
        if (rc) return -1;
        break;
    }
    case MS_PBC_CENTER_BB:
        if (ms_measure_minmax(&s, 0, lo, hi, err)) return -1;
        for (int k = 0; k < 3; k++) center[k] = 0.5 * (lo[k] + hi[k]);
        break;
    default:
        for (int k = 0; k < 3; k++) center[k] = 0.5 * (c->v[0][k] + c->v[1][k] + c->v[2][k]);
    }
    for (int k = 0; k < 3; k++)
        center[k] += o->shiftcenter[k] + o->shiftcenterrel[0] * c->v[0][k] +
                     o->shiftcenterrel[1] * c->v[1][k] + o->shiftcenterrel[2] * c->v[2][k];
    return 0;
}

typedef struct wrap_job {
    float *pos;
    const ms_pbc_groups *g;
    const ms_pbc_runs *runs;        /* when every group is one atom */
    const ms_pbc_cell *c;
    double origin[3];      /* the cell's lowest corner */
    int ortho;
} wrap_job;

/* The lattice vector t taking q (relative to the origin) into the cell. */
static void shift_into(const wrap_job *j, const double q[3], double t[3])
{
    const double (*v)[3] = j->c->v;
    double n[3];
    if (j->ortho) {
        double r[3] = {q[0], q[1], q[2]};
        for (int k = 2; k >= 0; k--) {
            double m = ms_pbc_floor(r[k] / v[k][k]);
            for (int d = 0; d < 3; d++) r[d] -= m * v[k][d];
        }
        for (int d = 0; d < 3; d++) t[d] = r[d] - q[d];
        return;
    }
    ms_pbc_frac(j->c, q, n);
    for (int k = 0; k < 3; k++) n[k] = -ms_pbc_floor(n[k]);
    ms_pbc_lattice(j->c, n, t);
}

static void move(float *p, const double t[3])
{
    if (t[0] == 0 && t[1] == 0 && t[2] == 0) return;
    for (int d = 0; d < 3; d++) p[d] = (float)(p[d] + t[d]);
}

/* Groups of one atom: runs of consecutive atoms through the vectorised loops. */
static void wrap_runs(void *ctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    const wrap_job *j = ctx;
    for (size_t k = begin; k < end; k++) {
        float *p = j->pos + 3 * (size_t)j->runs->run[k][0];
        if (j->ortho) ms_pbc_wrap_run_brick(p, j->runs->run[k][1], j->c, j->origin);
        else ms_pbc_wrap_run(p, j->runs->run[k][1], j->c, j->origin);
    }
}

static void wrap_range(void *ctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    const wrap_job *j = ctx;
    for (size_t k = begin; k < end; k++) {
        const uint32_t *at = j->g->atoms + j->g->start[k];
        size_t n = j->g->start[k + 1] - j->g->start[k];
        if (!n) continue;
        double q[3] = {0, 0, 0}, t[3];
        for (size_t i = 0; i < n; i++)
            for (int d = 0; d < 3; d++) q[d] += j->pos[3 * (size_t)at[i] + d];
        for (int d = 0; d < 3; d++) q[d] = q[d] / (double)n - j->origin[d];
        shift_into(j, q, t);
        for (size_t i = 0; i < n; i++) move(j->pos + 3 * (size_t)at[i], t);
    }
}

int ms_pbc_wrap(ms_molecule *m, size_t first, size_t last, const ms_pbc_wrap_opts *o,
                ms_error *err)
{
    if (ms_pbc_check_frames(m, first, last, err) || ms_mol_pin_frames(m, first, last, err))
        return -1;
    const ms_pbc_groups *g = o->groups;
    ms_pbc_runs runs = {0, NULL};
    if (g->n == g->start[g->n] && ms_pbc_runs_make(g->atoms, g->n, RUN_ATOMS, &runs)) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    int rc = 0;
    for (size_t f = first; rc == 0 && f <= last; f++) {
        ms_pbc_cell c;
        double center[3];
        ms_pbc_cell_make(m->frames[f].cell, &c);
        if ((rc = ms_pbc_center_of(m, f, &c, o, center, err))) break;
        wrap_job j = {m->frames[f].pos, g, &runs, &c, {0, 0, 0}, o->orthorhombic};
        for (int d = 0; d < 3; d++) {
            double half = o->orthorhombic ? c.v[d][d]
                                          : c.v[0][d] + c.v[1][d] + c.v[2][d];
            j.origin[d] = center[d] - 0.5 * half;
        }
        if (runs.run) ms_parallel_for(runs.n, 1, wrap_runs, &j);
        else ms_parallel_for(g->n, 4096, wrap_range, &j);
    }
    free(runs.run);
    return rc;
}
