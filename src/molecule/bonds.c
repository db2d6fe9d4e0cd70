/* bonds.c: bonds by distance through the cell grid of base/grid.h (linear in the number of
 * atoms, the search run on all cores), and the CSR bond table built from a list of pairs. */
#include "config.h"
#include "molecule/analysis.h"
#include "base/grid.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the search */

/* Pairs found by one thread, in fixed-size blocks so no growth ever copies or doubles:
 * the memory held is the pairs found plus at most one partly filled block. */
#define PAIR_BLOCK 32768
typedef struct pair_block {
    struct pair_block *next;
    size_t n;
    uint32_t pairs[2 * PAIR_BLOCK];
} pair_block;

typedef struct pair_buf {
    pair_block *head, *tail;
    size_t n;
    int failed;
} pair_buf;

typedef struct search_ctx {
    const ms_molecule *m;
    const float *pos;
    const ms_grid *g;
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
    if (!b->tail || b->tail->n == PAIR_BLOCK) {
        pair_block *blk = malloc(sizeof *blk);
        if (!blk) {
            b->failed = 1;
            return;
        }
        blk->next = NULL;
        blk->n = 0;
        if (b->tail) b->tail->next = blk;
        else b->head = blk;
        b->tail = blk;
    }
    uint32_t *p = b->tail->pairs + 2 * b->tail->n++;
    p[0] = i < j ? i : j;
    p[1] = i < j ? j : i;
    b->n++;
}

static void pair_buf_free(pair_buf *b)
{
    while (b->head) {
        pair_block *next = b->head->next;
        free(b->head);
        b->head = next;
    }
}

/* The pairs between items [a0, a1) and the run r; with same set, r starts at a0 and only
 * the pairs inside [a0, a1) after each item are taken. */
static void search_run(search_ctx *c, pair_buf *buf, uint32_t a0, uint32_t a1, ms_grid_run r,
                       int same)
{
    const uint32_t *items = c->g->items;
    for (uint32_t ia = a0; ia < a1; ia++) {
        uint32_t i = items[ia];
        for (uint32_t jb = same ? ia + 1 : r.begin; jb < r.end; jb++) {
            uint32_t j = items[jb];
            if (may_bond(c->m, i, j, c->pos)) push_pair(buf, i, j);
        }
    }
}

/* The slabs [begin, end) of cells: each cell's own pairs, then those with the forward half
 * of its neighbours, so every pair of cells is visited once. */
static void search_slabs(void *vctx, size_t begin, size_t end, int tid)
{
    search_ctx *c = vctx;
    const ms_grid *g = c->g;
    pair_buf *buf = &c->bufs[tid];
    for (long z = (long)begin; z < (long)end; z++)
        for (long y = 0; y < g->dim[1]; y++)
            for (long x = 0; x < g->dim[0]; x++) {
                size_t cell = ms_grid_index(g, x, y, z);
                uint32_t a0 = g->start[cell], a1 = g->start[cell + 1];
                if (a0 == a1) continue;
                ms_grid_run runs[5], own = {a0, a1};
                search_run(c, buf, a0, a1, own, 1);
                int nr = ms_grid_forward(g, x, y, z, runs);
                for (int r = 0; r < nr; r++) search_run(c, buf, a0, a1, runs[r], 0);
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
    ms_grid g;
    ms_grid_points pts = {pos, 3, NULL, n};
    /* at most two cells an atom: the grid's 8 bytes an atom keep a 1M-atom load's peak
     * memory where the slab-sorted grid before it had it */
    ms_grid_spec spec = {1.2f * rmax, 2.0, 4096.0, 1.1, 0};
    if (ms_grid_build(&g, &pts, &spec, err)) return -1;

    int nt = ms_threads_count();
    search_ctx ctx = {.m = m, .pos = pos, .g = &g, .bufs = calloc((size_t)nt, sizeof(pair_buf))};
    int failed = ctx.bufs == NULL;
    if (!failed) ms_parallel_for((size_t)g.dim[2], 1, search_slabs, &ctx);
    ms_grid_free(&g);

    size_t total = *npairs;
    for (int t = 0; ctx.bufs && t < nt; t++) {
        failed |= ctx.bufs[t].failed;
        total += ctx.bufs[t].n;
    }
    /* Exact size: the caller's array grows once, to what was found. */
    if (!failed && 2 * total > *cap) {
        uint32_t *p = realloc(*pairs, 2 * total * sizeof **pairs);
        if (p) {
            *pairs = p;
            *cap = 2 * total;
        } else {
            failed = 1;
        }
    }
    for (int t = 0; ctx.bufs && t < nt; t++) {
        for (pair_block *blk = ctx.bufs[t].head; blk && !failed; blk = blk->next) {
            memcpy(*pairs + 2 * *npairs, blk->pairs, 2 * blk->n * sizeof **pairs);
            *npairs += blk->n;
        }
        pair_buf_free(&ctx.bufs[t]);
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

/* Replace m's bond table by this one (untyped). */
static void set_bonds(ms_molecule *m, uint32_t *start, uint32_t *to, float *ord)
{
    free(m->bonds.start);
    free(m->bonds.to);
    free(m->bonds.order);
    free(m->bonds.type);
    m->bonds.start = start;
    m->bonds.to = to;
    m->bonds.order = ord;
    m->bonds.type = NULL;
    m->has_bonds = 1;
}

int ms_bonds_build(ms_molecule *m, const uint32_t *pairs, size_t npairs, const float *order,
                   ms_error *err)
{
    size_t n = m->atoms.n;
    uint32_t *start = calloc(n + 2, sizeof *start);
    if (!start) goto oom;
    size_t used = 0;
    /* Pairs given in order (i < j, ascending by i then j, as a js file lists them) fill
     * every row already sorted and free of duplicates: no row needs sorting then. */
    int ordered = 1;
    uint64_t last = 0;
    for (size_t k = 0; k < npairs; k++) {
        uint32_t i = pairs[2 * k], j = pairs[2 * k + 1];
        if (i == j || i >= n || j >= n) {
            ordered = 0;
            continue;
        }
        uint64_t key = (uint64_t)i << 32 | j;
        ordered &= i < j && (k == 0 || key > last);
        last = key;
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
    /* start[i] is now where row i begins (row i-1's fill cursor ended there). Unless the
     * pairs came in order, sort each row and drop duplicate partners, compacting in place. */
    if (ordered) {
        set_bonds(m, start, to, ord);
        return 0;
    }
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
    set_bonds(m, start, to, ord);
    return 0;
oom:
    ms_error_set(err, "out of memory building the bond table (%zu bonds)", npairs);
    return -1;
}

/* Where atom j is among atom i's partners (rows are sorted), or -1. */
static long bond_slot(const ms_bonds *b, uint32_t i, uint32_t j)
{
    uint32_t lo = b->start[i], hi = b->start[i + 1];
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (b->to[mid] < j) lo = mid + 1;
        else hi = mid;
    }
    return lo < b->start[i + 1] && b->to[lo] == j ? (long)lo : -1;
}

int ms_bonds_set_types(ms_molecule *m, const uint32_t *pairs, const ms_str *types,
                       size_t npairs, ms_error *err)
{
    ms_bonds *b = &m->bonds;
    size_t n = m->atoms.n, nb = m->has_bonds ? b->start[n] : 0;
    if (!nb) return 0;
    if (!b->type) {
        ms_str blank = ms_strtab_intern_cstr(m->strings, "");
        if (blank == MS_STR_NONE || !(b->type = ms_alloc_array(nb, sizeof *b->type))) {
            ms_error_set(err, "out of memory for bond types");
            return -1;
        }
        for (size_t k = 0; k < nb; k++) b->type[k] = blank;
    }
    for (size_t k = 0; k < npairs; k++) {
        uint32_t i = pairs[2 * k], j = pairs[2 * k + 1];
        if (types[k] == MS_STR_NONE || i >= n || j >= n) continue;
        long a = bond_slot(b, i, j), c = bond_slot(b, j, i);
        if (a >= 0) b->type[a] = types[k];
        if (c >= 0) b->type[c] = types[k];
    }
    return 0;
}
