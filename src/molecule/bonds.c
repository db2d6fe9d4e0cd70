/* bonds.c: bonds by distance through a uniform cell grid (linear in the number of atoms,
 * run on all cores), and the CSR bond table built from a list of pairs. */
#include "config.h"
#include "molecule/analysis.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the cell grid */

typedef struct bond_grid {
    float origin[3], cell;
    int dim[3];
    uint32_t *cell_start;  /* ncells + 1 */
    uint32_t *atoms;       /* atom indices sorted by cell */
    size_t ncells;
} bond_grid;

static int grid_build(bond_grid *g, const float *pos, size_t n, float cutoff, ms_error *err)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t nvalid = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = pos + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        for (int k = 0; k < 3; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
        nvalid++;
    }
    memset(g, 0, sizeof *g);
    if (nvalid == 0) return 0;
    /* Cells at least the cutoff wide, and never more than about two per atom, so a sparse
     * system spread over a huge box does not need a huge grid. */
    double vol = 1.0, span[3];
    for (int k = 0; k < 3; k++) {
        span[k] = (double)hi[k] - (double)lo[k]; /* in double: never overflows */
        vol *= span[k] + cutoff;
    }
    double cell = cutoff;
    double mincell = cbrt(vol / (2.0 * (double)nvalid + 1.0));
    if (cell < mincell) cell = mincell;
    for (;;) {
        /* Count cells in double: a huge span must not overflow an int before the check. */
        double dims[3], ncells = 1.0;
        for (int k = 0; k < 3; k++) {
            dims[k] = floor(span[k] / cell) + 1.0;
            ncells *= dims[k];
        }
        if (ncells <= 4.0 * (double)nvalid + 64.0) {
            for (int k = 0; k < 3; k++) g->dim[k] = (int)dims[k];
            g->ncells = (size_t)ncells;
            break;
        }
        cell *= 1.26;
    }
    g->cell = (float)cell;
    memcpy(g->origin, lo, sizeof lo);
    g->cell_start = calloc(g->ncells + 1, sizeof *g->cell_start);
    g->atoms = ms_alloc_array(nvalid, sizeof *g->atoms);
    uint32_t *cell_of = ms_alloc_array(n, sizeof *cell_of);
    if (!g->cell_start || !g->atoms || !cell_of) {
        free(cell_of);
        free(g->cell_start);
        free(g->atoms);
        memset(g, 0, sizeof *g);
        ms_error_set(err, "out of memory for the bond search grid of %zu atoms", n);
        return -1;
    }
    float inv = 1.0f / g->cell;
    for (size_t i = 0; i < n; i++) {
        const float *p = pos + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            cell_of[i] = UINT32_MAX;
            continue;
        }
        int c[3];
        for (int k = 0; k < 3; k++) {
            c[k] = (int)((p[k] - lo[k]) * inv);
            if (c[k] >= g->dim[k]) c[k] = g->dim[k] - 1;
        }
        cell_of[i] = (uint32_t)(((size_t)c[2] * g->dim[1] + c[1]) * g->dim[0] + c[0]);
        g->cell_start[cell_of[i] + 1]++;
    }
    for (size_t c = 0; c < g->ncells; c++) g->cell_start[c + 1] += g->cell_start[c];
    /* Counting sort, stable: atoms keep index order inside a cell. */
    uint32_t *fill = ms_alloc_array(g->ncells, sizeof *fill);
    if (!fill) {
        free(cell_of);
        free(g->cell_start);
        free(g->atoms);
        memset(g, 0, sizeof *g);
        ms_error_set(err, "out of memory for the bond search grid of %zu atoms", n);
        return -1;
    }
    memcpy(fill, g->cell_start, g->ncells * sizeof *fill);
    for (size_t i = 0; i < n; i++)
        if (cell_of[i] != UINT32_MAX) g->atoms[fill[cell_of[i]]++] = (uint32_t)i;
    free(fill);
    free(cell_of);
    return 0;
}

static void grid_free(bond_grid *g)
{
    free(g->cell_start);
    free(g->atoms);
}

/* ---------------------------------------------------------------- the search */

typedef struct pair_buf {
    uint32_t *pairs;
    size_t n, cap;
    int failed;
} pair_buf;

typedef struct search_ctx {
    const ms_molecule *m;
    const float *pos;
    const bond_grid *g;
    pair_buf *bufs;  /* one per thread */
} search_ctx;

static int may_bond(const ms_molecule *m, uint32_t i, uint32_t j, const float *pos)
{
    const ms_atoms *a = &m->atoms;
    if ((a->flags[i] & a->flags[j] & MS_AF_HYDROGEN)) return 0;
    char ai = a->altloc[i], aj = a->altloc[j];
    if (ai && aj && ai != aj) return 0;
    const float *p = pos + 3 * i, *q = pos + 3 * j;
    float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    float d2 = dx * dx + dy * dy + dz * dz;
    float cut = 0.6f * (a->radius[i] + a->radius[j]);
    return d2 < cut * cut && d2 > 1e-6f;
}

static void push_pair(pair_buf *b, uint32_t i, uint32_t j)
{
    if (b->failed) return;
    if (ms_grow((void **)&b->pairs, &b->cap, 2 * (b->n + 1), sizeof *b->pairs)) {
        b->failed = 1;
        return;
    }
    b->pairs[2 * b->n] = i < j ? i : j;
    b->pairs[2 * b->n + 1] = i < j ? j : i;
    b->n++;
}

/* The 13 forward neighbours plus the cell itself: every pair of cells is visited once. */
static const int half_shell[14][3] = {
    {0, 0, 0},  {1, 0, 0},   {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},  {-1, -1, 1}, {0, -1, 1},
    {1, -1, 1}, {-1, 0, 1},  {0, 0, 1},  {1, 0, 1},  {-1, 1, 1}, {0, 1, 1},   {1, 1, 1}};

static void search_cells(void *vctx, size_t begin, size_t end, int tid)
{
    search_ctx *c = vctx;
    const bond_grid *g = c->g;
    pair_buf *buf = &c->bufs[tid];
    for (size_t cell = begin; cell < end; cell++) {
        uint32_t a0 = g->cell_start[cell], a1 = g->cell_start[cell + 1];
        if (a0 == a1) continue;
        int cx = (int)(cell % (size_t)g->dim[0]);
        int cy = (int)((cell / (size_t)g->dim[0]) % (size_t)g->dim[1]);
        int cz = (int)(cell / ((size_t)g->dim[0] * g->dim[1]));
        for (int s = 0; s < 14; s++) {
            int nx = cx + half_shell[s][0], ny = cy + half_shell[s][1], nz = cz + half_shell[s][2];
            if (nx < 0 || ny < 0 || nz < 0 || nx >= g->dim[0] || ny >= g->dim[1] || nz >= g->dim[2])
                continue;
            size_t other = ((size_t)nz * g->dim[1] + ny) * g->dim[0] + nx;
            uint32_t b0 = g->cell_start[other], b1 = g->cell_start[other + 1];
            for (uint32_t ia = a0; ia < a1; ia++) {
                uint32_t i = g->atoms[ia];
                for (uint32_t jb = (s == 0 ? ia + 1 : b0); jb < b1; jb++) {
                    uint32_t j = g->atoms[jb];
                    if (may_bond(c->m, i, j, c->pos)) push_pair(buf, i, j);
                }
            }
        }
    }
}

int ms_bond_search(const ms_molecule *m, const float *pos, uint32_t **pairs, size_t *npairs,
                   size_t *cap, ms_error *err)
{
    size_t n = m->atoms.n;
    if (n < 2) return 0;
    float rmax = 0.0f;
    for (size_t i = 0; i < n; i++)
        if (m->atoms.radius[i] > rmax) rmax = m->atoms.radius[i];
    if (rmax <= 0.0f) return 0;
    bond_grid g;
    if (grid_build(&g, pos, n, 1.2f * rmax, err)) return -1;
    if (g.ncells == 0) return 0;

    int nt = ms_threads_count();
    search_ctx ctx = {.m = m, .pos = pos, .g = &g, .bufs = calloc((size_t)nt, sizeof(pair_buf))};
    if (!ctx.bufs) {
        grid_free(&g);
        ms_error_set(err, "out of memory in the bond search");
        return -1;
    }
    ms_parallel_for(g.ncells, 4096, search_cells, &ctx);
    grid_free(&g);

    int failed = 0;
    size_t total = *npairs;
    for (int t = 0; t < nt; t++) {
        failed |= ctx.bufs[t].failed;
        total += ctx.bufs[t].n;
    }
    if (!failed && ms_grow((void **)pairs, cap, 2 * total, sizeof **pairs)) failed = 1;
    for (int t = 0; t < nt; t++) {
        if (!failed && ctx.bufs[t].n) {
            memcpy(*pairs + 2 * *npairs, ctx.bufs[t].pairs, 2 * ctx.bufs[t].n * sizeof **pairs);
            *npairs += ctx.bufs[t].n;
        }
        free(ctx.bufs[t].pairs);
    }
    free(ctx.bufs);
    if (failed) {
        ms_error_set(err, "out of memory storing bonds of %zu atoms", n);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- CSR table */

static void sort_row(uint32_t *to, float *order, uint32_t n)
{
    for (uint32_t i = 1; i < n; i++) {
        uint32_t v = to[i];
        float o = order ? order[i] : 0.0f;
        uint32_t j = i;
        while (j > 0 && to[j - 1] > v) {
            to[j] = to[j - 1];
            if (order) order[j] = order[j - 1];
            j--;
        }
        to[j] = v;
        if (order) order[j] = o;
    }
}

int ms_bonds_build(ms_molecule *m, const uint32_t *pairs, size_t npairs, const float *order,
                   ms_error *err)
{
    size_t n = m->atoms.n;
    uint32_t *start = calloc(n + 2, sizeof *start);
    if (!start) goto oom;
    size_t used = 0;
    for (size_t k = 0; k < npairs; k++) {
        uint32_t i = pairs[2 * k], j = pairs[2 * k + 1];
        if (i == j || i >= n || j >= n) continue;
        start[i + 2]++;
        start[j + 2]++;
        used++;
    }
    if (used > UINT32_MAX / 2) {
        free(start);
        ms_error_set(err, "too many bonds (%zu)", used);
        return -1;
    }
    for (size_t i = 0; i < n; i++) start[i + 2] += start[i + 1];
    uint32_t *to = ms_alloc_array(2 * used, sizeof *to);
    float *ord = order ? ms_alloc_array(2 * used, sizeof *ord) : NULL;
    if (!to || (order && !ord)) {
        free(to);
        free(ord);
        free(start);
        goto oom;
    }
    /* start[i+1] is the fill cursor of row i; after filling it is row i's end. */
    for (size_t k = 0; k < npairs; k++) {
        uint32_t i = pairs[2 * k], j = pairs[2 * k + 1];
        if (i == j || i >= n || j >= n) continue;
        uint32_t si = start[i + 1]++, sj = start[j + 1]++;
        to[si] = j;
        to[sj] = i;
        if (ord) ord[si] = ord[sj] = order[k];
    }
    /* Sort each row and drop duplicate partners, compacting in place. */
    uint32_t w = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t b = start[i], e = start[i + 1];
        sort_row(to + b, ord ? ord + b : NULL, e - b);
        start[i] = w;
        for (uint32_t k = b; k < e; k++) {
            if (k > b && to[k] == to[k - 1]) continue;
            to[w] = to[k];
            if (ord) ord[w] = ord[k];
            w++;
        }
    }
    start[n] = w;
    uint32_t *shrunk = realloc(to, (w ? w : 1) * sizeof *to);
    if (shrunk) to = shrunk;
    if (ord) {
        float *s2 = realloc(ord, (w ? w : 1) * sizeof *ord);
        if (s2) ord = s2;
    }
    free(m->bonds.start);
    free(m->bonds.to);
    free(m->bonds.order);
    free(m->bonds.type);
    m->bonds.start = start;
    m->bonds.to = to;
    m->bonds.order = ord;
    m->bonds.type = NULL;
    m->has_bonds = 1;
    return 0;
oom:
    ms_error_set(err, "out of memory building the bond table (%zu bonds)", npairs);
    return -1;
}
