/* wrap.c: `pbc wrap`: every group (an atom alone, or a compound by its mean position) is
 * moved by the lattice vector that puts it into the cell centred on the wrapping centre:
 * the parallelepiped A B C, or with orthorhombic the brick Ax x By x Cz (z first, then y,
 * then x, which the triangular cell allows). Groups run in parallel, frame after frame. */
#include "config.h"
#include "base/threads.h"
#include "measure/measure.h"
#include "pbc/internal.h"

#include <math.h>
#include <stdlib.h>

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

/* Groups of one atom: no means, no indirection through the groups. */
static void wrap_atoms(const wrap_job *j, size_t begin, size_t end)
{
    const uint32_t *at = j->g->atoms;
    for (size_t k = begin; k < end; k++) {
        float *p = j->pos + 3 * (size_t)at[k];
        double q[3] = {p[0] - j->origin[0], p[1] - j->origin[1], p[2] - j->origin[2]}, t[3];
        shift_into(j, q, t);
        move(p, t);
    }
}

static void wrap_range(void *ctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    const wrap_job *j = ctx;
    if (j->g->n == j->g->start[j->g->n]) {
        wrap_atoms(j, begin, end);
        return;
    }
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
    if (ms_pbc_check_frames(m, first, last, err)) return -1;
    for (size_t f = first; f <= last; f++) {
        ms_pbc_cell c;
        double center[3];
        ms_pbc_cell_make(m->frames[f].cell, &c);
        if (ms_pbc_center_of(m, f, &c, o, center, err)) return -1;
        wrap_job j = {m->frames[f].pos, o->groups, &c, {0, 0, 0}, o->orthorhombic};
        for (int d = 0; d < 3; d++) {
            double half = o->orthorhombic ? c.v[d][d]
                                          : c.v[0][d] + c.v[1][d] + c.v[2][d];
            j.origin[d] = center[d] - 0.5 * half;
        }
        ms_parallel_for(o->groups->n, 4096, wrap_range, &j);
    }
    return 0;
}
