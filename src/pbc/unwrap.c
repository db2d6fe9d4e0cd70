/* unwrap.c: `pbc unwrap` and `pbc join`. Both move an atom by the lattice vector that
 * brings it nearest a reference point (rounding its fractional offset): for unwrap the
 * atom's own position in the frame before (already unwrapped), for join its compound's
 * reference atom or, with the bond list, the bonded atom it was reached from. Unwrap runs
 * through the vectorised loops of kernels.c. */
#include "config.h"
#include "base/threads.h"
#include "pbc/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Move p to the image nearest r. */
static void nearest_image(const ms_pbc_cell *c, float *p, const float *r)
{
    double d[3] = {(double)p[0] - r[0], (double)p[1] - r[1], (double)p[2] - r[2]}, n[3], t[3];
    ms_pbc_frac(c, d, n);
    for (int k = 0; k < 3; k++) n[k] = ms_pbc_round(n[k]);
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) return;
    ms_pbc_lattice(c, n, t);
    for (int k = 0; k < 3; k++) p[k] = (float)(p[k] - t[k]);
}

/* Unwrap goes by runs of consecutive atoms, each through every frame before the next run,
 * so that the previous frame's atoms are still in the cache. */
enum { RUN_ATOMS = 4096 };

typedef struct unwrap_job {
    const ms_molecule *m;
    size_t first, last;
    const ms_pbc_cell *cells;       /* frames first..last */
    const ms_pbc_runs *runs;
} unwrap_job;

static void unwrap_range(void *ctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    const unwrap_job *j = ctx;
    for (size_t k = begin; k < end; k++) {
        size_t a = 3 * (size_t)j->runs->run[k][0], n = j->runs->run[k][1];
        for (size_t f = j->first + 1; f <= j->last; f++)
            ms_pbc_unwrap_run(j->m->frames[f].pos + a, j->m->frames[f - 1].pos + a, n,
                              &j->cells[f - j->first]);
    }
}

int ms_pbc_unwrap(ms_molecule *m, size_t first, size_t last, const uint32_t *atoms, size_t n,
                  ms_error *err)
{
    if (ms_pbc_check_frames(m, first, last, err) || ms_mol_pin_frames(m, first, last, err))
        return -1;
    ms_pbc_cell *cells = ms_alloc_array(last - first + 1, sizeof *cells);
    ms_pbc_runs runs = {0, NULL};
    if (!cells || ms_pbc_runs_make(atoms, n, RUN_ATOMS, &runs)) {
        free(cells);
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (size_t f = first; f <= last; f++) ms_pbc_cell_make(m->frames[f].cell, &cells[f - first]);
    unwrap_job j = {m, first, last, cells, &runs};
    ms_parallel_for(runs.n, 1, unwrap_range, &j);
    free(runs.run);
    free(cells);
    return 0;
}

/* ---------------------------------------------------------------- join */

/* The order atoms are joined in and the atom each is joined to (parent[i] for order[i];
 * the reference atom first, its own parent), laid out compound by compound like g. */
typedef struct join_plan {
    const ms_pbc_groups *g;
    uint32_t *order, *parent;
} join_plan;

static size_t reference_of(const ms_pbc_groups *g, size_t k, const uint8_t *ref)
{
    for (uint32_t i = g->start[k]; ref && i < g->start[k + 1]; i++)
        if (ref[g->atoms[i]]) return i;
    return g->start[k];
}

/* Breadth-first from the reference over bonds inside the compound (comp[atom] == k + 1);
 * atoms no bond reaches are joined to the reference. */
static void plan_compound(const ms_molecule *m, join_plan *p, size_t k, const uint8_t *ref,
                          int bondlist, uint32_t *comp, uint8_t *seen)
{
    const ms_pbc_groups *g = p->g;
    uint32_t s = g->start[k], e = g->start[k + 1], r = g->atoms[reference_of(g, k, ref)];
    uint32_t *order = p->order, *parent = p->parent, fill = s;
    order[fill] = r, parent[fill++] = r, seen[r] = 1;
    for (uint32_t q = s; bondlist && m->has_bonds && q < fill; q++) {
        uint32_t a = order[q];
        for (uint32_t b = m->bonds.start[a]; b < m->bonds.start[a + 1]; b++) {
            uint32_t o = m->bonds.to[b];
            if (comp[o] != k + 1 || seen[o]) continue;
            seen[o] = 1, order[fill] = o, parent[fill++] = a;
        }
    }
    for (uint32_t i = s; i < e; i++)
        if (!seen[g->atoms[i]]) seen[g->atoms[i]] = 1, order[fill] = g->atoms[i], parent[fill++] = r;
}

static int plan_make(const ms_molecule *m, const ms_pbc_groups *g, const uint8_t *ref,
                     int bondlist, join_plan *p)
{
    size_t n = g->start[g->n];
    p->g = g;
    p->order = ms_alloc_array(n ? n : 1, sizeof *p->order);
    p->parent = ms_alloc_array(n ? n : 1, sizeof *p->parent);
    uint32_t *comp = calloc(m->atoms.n ? m->atoms.n : 1, sizeof *comp);
    uint8_t *seen = calloc(m->atoms.n ? m->atoms.n : 1, 1);
    int ok = p->order && p->parent && comp && seen;
    for (size_t k = 0; ok && k < g->n; k++)
        for (uint32_t i = g->start[k]; i < g->start[k + 1]; i++) comp[g->atoms[i]] = (uint32_t)k + 1;
    for (size_t k = 0; ok && k < g->n; k++)
        if (g->start[k + 1] > g->start[k]) plan_compound(m, p, k, ref, bondlist, comp, seen);
    free(comp);
    free(seen);
    return ok ? 0 : -1;
}

typedef struct join_job {
    const join_plan *p;
    const ms_pbc_cell *c;
    float *pos;
} join_job;

static void join_range(void *ctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    const join_job *j = ctx;
    const ms_pbc_groups *g = j->p->g;
    for (size_t k = begin; k < end; k++)
        for (uint32_t i = g->start[k] + 1; i < g->start[k + 1]; i++)
            nearest_image(j->c, j->pos + 3 * (size_t)j->p->order[i],
                          j->pos + 3 * (size_t)j->p->parent[i]);
}

int ms_pbc_join(ms_molecule *m, size_t first, size_t last, const ms_pbc_groups *g,
                const uint8_t *ref, int bondlist, ms_error *err)
{
    if (ms_pbc_check_frames(m, first, last, err) || ms_mol_pin_frames(m, first, last, err))
        return -1;
    join_plan p;
    if (plan_make(m, g, ref, bondlist, &p)) {
        free(p.order);
        free(p.parent);
        ms_error_set(err, "out of memory planning the join of %zu compounds", g->n);
        return -1;
    }
    for (size_t f = first; f <= last; f++) {
        ms_pbc_cell c;
        ms_pbc_cell_make(m->frames[f].cell, &c);
        join_job j = {&p, &c, m->frames[f].pos};
        ms_parallel_for(g->n, 1024, join_range, &j);
    }
    free(p.order);
    free(p.parent);
    return 0;
}
