/* hbond.c: DSSP's backbone hydrogen bonds. Each N-H (the hydrogen placed 1 A from N, away
 * from the previous residue's C=O) is scored against each C=O by the electrostatic energy
 *   E = 0.084 * 332 * (1/rON + 1/rCH - 1/rOH - 1/rCN)  kcal/mol,
 * and keeps its two best acceptors. Candidate pairs come from a cell grid on the CA atoms
 * (CA-CA < 9 A), so the search is linear; donors are scored in parallel, each by one thread,
 * which keeps the result independent of the schedule. */
#include "config.h"
#include "ss/ssint.h"
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

typedef struct ca_grid {
    double origin[3], cell;
    long dim[3];
    uint32_t *start;   /* ncells + 1 */
    uint32_t *res;     /* residues by cell */
} ca_grid;

static long cell_coord(const ca_grid *g, const float *p, int k)
{
    long v = (long)floor((p[k] - g->origin[k]) / g->cell);
    return v < 0 ? 0 : v >= g->dim[k] ? g->dim[k] - 1 : v;
}

static size_t cell_of(const ca_grid *g, const float *p)
{
    return ((size_t)cell_coord(g, p, 2) * (size_t)g->dim[1] + (size_t)cell_coord(g, p, 1)) *
               (size_t)g->dim[0] + (size_t)cell_coord(g, p, 0);
}

/* Cells at least the cutoff wide, at most about four per residue. */
static size_t grid_shape(ca_grid *g, const ms_ss_chain *c)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < c->n; k++)
        for (int d = 0; d < 3; d++) {
            double v = ms_ss_atom(c, k, 1)[d];
            lo[d] = v < lo[d] ? v : lo[d];
            hi[d] = v > hi[d] ? v : hi[d];
        }
    double limit = 4.0 * (double)c->n + 64.0;
    for (g->cell = MS_SS_CA_CUTOFF;; g->cell *= 1.26) {
        double cells = 1.0;
        for (int d = 0; d < 3; d++) cells *= floor((hi[d] - lo[d]) / g->cell) + 1.0;
        if (cells <= limit) break;
    }
    size_t ncells = 1;
    for (int d = 0; d < 3; d++) {
        g->origin[d] = lo[d];
        g->dim[d] = (long)floor((hi[d] - lo[d]) / g->cell) + 1;
        ncells *= (size_t)g->dim[d];
    }
    return ncells;
}

static int grid_build(ca_grid *g, const ms_ss_chain *c)
{
    size_t ncells = grid_shape(g, c);
    uint32_t *which = ms_alloc_array(c->n, sizeof *which);
    g->start = calloc(ncells + 1, sizeof *g->start);
    g->res = ms_alloc_array(c->n, sizeof *g->res);
    if (!which || !g->start || !g->res) {
        free(which);
        return -1;
    }
    for (size_t k = 0; k < c->n; k++) {
        which[k] = (uint32_t)cell_of(g, ms_ss_atom(c, k, 1));
        g->start[which[k] + 1]++;
    }
    for (size_t i = 0; i < ncells; i++) g->start[i + 1] += g->start[i];
    for (size_t k = 0; k < c->n; k++) g->res[g->start[which[k]]++] = (uint32_t)k;
    for (size_t i = ncells; i > 0; i--) g->start[i] = g->start[i - 1];   /* undo the bumps */
    g->start[0] = 0;
    free(which);
    return 0;
}

/* ---------------------------------------------------------------- the search */

typedef struct search_job {
    ms_ss_chain *c;
    const ca_grid *g;
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
static void search_donor(ms_ss_chain *c, const ca_grid *g, size_t d)
{
    const float *ca = ms_ss_atom(c, d, 1);
    long x0 = cell_coord(g, ca, 0), y0 = cell_coord(g, ca, 1), z0 = cell_coord(g, ca, 2);
    const double cut2 = (double)MS_SS_CA_CUTOFF * MS_SS_CA_CUTOFF;
    for (long z = MS_MAX(z0 - 1, 0); z <= MS_MIN(z0 + 1, g->dim[2] - 1); z++)
        for (long y = MS_MAX(y0 - 1, 0); y <= MS_MIN(y0 + 1, g->dim[1] - 1); y++)
            for (long x = MS_MAX(x0 - 1, 0); x <= MS_MIN(x0 + 1, g->dim[0] - 1); x++) {
                size_t cell = ((size_t)z * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[0] +
                              (size_t)x;
                for (uint32_t q = g->start[cell]; q < g->start[cell + 1]; q++) {
                    size_t a = g->res[q];
                    if (a == d || a + 1 == d) continue;
                    if (dist2(ca, ms_ss_atom(c, a, 1)) >= cut2) continue;
                    float e = energy(c, d, a);
                    if (e < 0) keep_best(c, d, a, e);
                }
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
    ca_grid g = {{0}, 0, {0}, NULL, NULL};
    if (grid_build(&g, c)) {
        free(g.start);
        free(g.res);
        ms_error_set(err, "out of memory for the hydrogen bond grid of %zu residues", c->n);
        return -1;
    }
    search_job j = {c, &g};
    ms_parallel_for(c->n, 512, search_range, &j);
    free(g.start);
    free(g.res);
    return 0;
}
