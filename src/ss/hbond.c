/* hbond.c: DSSP's backbone hydrogen bonds. Each N-H (the hydrogen placed 1 A from N, away
 * from the previous residue's C=O) is scored against each C=O by the electrostatic energy
 *   E = 0.084 * 332 * (1/rON + 1/rCH - 1/rOH - 1/rCN)  kcal/mol,
 * and keeps its two best acceptors. Candidate pairs come from a cell grid on the CA atoms
 * (CA-CA < 9 A), so the search is linear; donors are scored in parallel, each by one thread,
 * which keeps the result independent of the schedule. */
#include "config.h"
#include "ss/ssint.h"
#include "base/grid.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double dist2(const float *a, const float *b)
{
    double dx = (double)a[0] - b[0], dy = (double)a[1] - b[1], dz = (double)a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

static double dist(const float *a, const float *b) { return sqrt(dist2(a, b)); }

/* Breaks (a new chain, or C(k-1)-N(k) too long), pieces and amide hydrogens. */
static void place_hydrogens(ms_ss_chain *c)
{
    uint32_t piece = 0;
    for (size_t k = 0; k < c->n; k++) {
        const float *n = ms_ss_atom(c, k, 0);
        float *h = c->h + 3 * k;
        int joined = k > 0 && c->seg[k] == c->seg[k - 1] &&
                     dist(ms_ss_atom(c, k - 1, 2), n) <= MS_SS_PEPTIDE_MAX;
        if (k > 0 && !joined) piece++;
        c->piece[k] = piece;
        c->donor[k] = (uint8_t)(joined && !c->proline[k]);
        memcpy(h, n, 3 * sizeof *h);
        if (!joined) continue;
        const float *pc = ms_ss_atom(c, k - 1, 2), *po = ms_ss_atom(c, k - 1, 3);
        double co = dist(pc, po);
        if (co > 0)
            for (int d = 0; d < 3; d++) h[d] = (float)(n[d] + (pc[d] - po[d]) / co);
    }
}

/* The energy of the bond N-H(d) ... O=C(a), rounded to 1 cal/mol as DSSP stores it. */
static float energy(const ms_ss_chain *c, size_t d, size_t a)
{
    const float *n = ms_ss_atom(c, d, 0), *h = c->h + 3 * d;
    const float *cc = ms_ss_atom(c, a, 2), *o = ms_ss_atom(c, a, 3);
    double ron = dist(o, n), rch = dist(cc, h), roh = dist(o, h), rcn = dist(cc, n);
    if (ron < 0.5 || rch < 0.5 || roh < 0.5 || rcn < 0.5) return MS_SS_ENERGY_MIN;
    double e = 0.084 * 332.0 * (1.0 / ron + 1.0 / rch - 1.0 / roh - 1.0 / rcn);
    e = round(e * 1000.0) / 1000.0;
    return e < MS_SS_ENERGY_MIN ? MS_SS_ENERGY_MIN : (float)e;
}

/* ---------------------------------------------------------------- the CA grid */

/* The residues by the cell of their CA (base/grid.h): cells at least the cutoff wide, at
 * most about four per residue. */
static int grid_build(ms_grid *g, const ms_ss_chain *c, ms_error *err)
{
    ms_grid_points p = {c->bb + 3, 12, NULL, c->n};
    ms_grid_spec spec = {MS_SS_CA_CUTOFF, 4.0, 64.0, 1.26, 0};
    return ms_grid_build(g, &p, &spec, err);
}

/* ---------------------------------------------------------------- the search */

typedef struct search_job {
    ms_ss_chain *c;
    const ms_grid *g;
} search_job;

static void keep_best(ms_ss_chain *c, size_t d, size_t a, float e)
{
    int32_t *p = c->acc + 2 * d;
    float *be = c->energy + 2 * d;
    if (e < be[0]) {
        p[1] = p[0], be[1] = be[0];
        p[0] = (int32_t)a, be[0] = e;
    } else if (e < be[1]) {
        p[1] = (int32_t)a, be[1] = e;
    }
}

/* Every acceptor of donor d in the 27 cells around its CA. The C=O of the residue just
 * before d is left out, as DSSP does. */
static void search_donor(ms_ss_chain *c, const ms_grid *g, size_t d)
{
    const float *ca = ms_ss_atom(c, d, 1);
    const double cut2 = (double)MS_SS_CA_CUTOFF * MS_SS_CA_CUTOFF;
    ms_grid_run runs[9];
    int nr = ms_grid_near(g, ca, runs);
    for (int r = 0; r < nr; r++)
        for (uint32_t q = runs[r].begin; q < runs[r].end; q++) {
            size_t a = g->items[q];
            if (a == d || a + 1 == d) continue;
            if (dist2(ca, ms_ss_atom(c, a, 1)) >= cut2) continue;
            float e = energy(c, d, a);
            if (e < 0) keep_best(c, d, a, e);
        }
}

static void search_range(void *ctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    search_job *j = ctx;
    for (size_t d = begin; d < end; d++)
        if (j->c->donor[d]) search_donor(j->c, j->g, d);
}

int ms_ss_hbonds(ms_ss_chain *c, ms_error *err)
{
    if (c->n > INT32_MAX) {
        ms_error_set(err, "too many residues for secondary structure (%zu)", c->n);
        return -1;
    }
    place_hydrogens(c);
    for (size_t k = 0; k < 2 * c->n; k++) {
        c->acc[k] = -1;
        c->energy[k] = 0.0f;
    }
    if (c->n == 0) return 0;
    ms_grid g;
    if (grid_build(&g, c, err)) return -1;
    search_job j = {c, &g};
    ms_parallel_for(c->n, 512, search_range, &j);
    ms_grid_free(&g);
    return 0;
}
