/* bonds.c: bonds by distance through a uniform cell grid (linear in the number of atoms,
 * run on all cores), and the CSR bond table built from a list of pairs. */
#include "config.h"
#include "molecule/analysis.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the cell grid */

/* Atoms sorted by (z, y, x) cell of a grid whose cells are the bond cutoff wide. Only the
 * sorted index array (4 bytes an atom) and one start per z-slab are kept for the whole box;
 * a thread searching slab k builds the 2D cell starts of slabs k and k+1 in scratch arrays,
 * so memory does not grow with the volume of a sparse box. */
typedef struct slab_grid {
    float origin[3], cell;
    int dim[3];
    uint32_t *atoms;       /* sorted by cell */
    uint32_t *slab_start;  /* dim[2] + 1 */
    size_t max_slab;       /* most atoms in one slab */
} slab_grid;

static void grid_free(slab_grid *g)
{
    free(g->atoms);
    free(g->slab_start);
    memset(g, 0, sizeof *g);
}

static int finite3(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static int cell_coord(const slab_grid *g, const float *p, int k)
{
    double v = ((double)p[k] - (double)g->origin[k]) / (double)g->cell;
    return v < 0.0 ? 0 : v >= (double)g->dim[k] ? g->dim[k] - 1 : (int)v;
}

static size_t cell2d(const slab_grid *g, const float *p)
{
    return (size_t)cell_coord(g, p, 1) * (size_t)g->dim[0] + (size_t)cell_coord(g, p, 0);
}

static size_t ncells2d(const slab_grid *g) { return (size_t)g->dim[0] * (size_t)g->dim[1]; }

/* Choose cell size and dimensions: the cutoff, grown while the grid would have far more
 * cells than atoms (every cell is visited once per search). */
static size_t grid_size(slab_grid *g, const float *pos, size_t n, float cutoff)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t nvalid = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = pos + 3 * i;
        if (!finite3(p)) continue;
        for (int k = 0; k < 3; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
        nvalid++;
    }
    if (nvalid == 0) return 0;
    /* Spans and cell counts in double: a huge coordinate range must not overflow. */
    double span[3];
    for (int k = 0; k < 3; k++) span[k] = (double)hi[k] - (double)lo[k];
    double cell = cutoff, limit = 8.0 * (double)nvalid + 1e6;
    for (;;) {
        double cells = 1.0;
        for (int k = 0; k < 3; k++) cells *= floor(span[k] / cell) + 1.0;
        if (cells <= limit) break;
        cell *= 1.1;
    }
    g->cell = (float)cell;
    for (int k = 0; k < 3; k++) {
        g->origin[k] = lo[k];
        g->dim[k] = (int)floor(span[k] / cell) + 1;
    }
    return nvalid;
}

typedef struct sort_ctx {
    slab_grid *g;
    const float *pos;
    uint32_t **count;   /* per thread: ncells2d + 1 */
    uint32_t **tmp;     /* per thread: max_slab */
} sort_ctx;

/* Counting-sort the atoms of each slab by their 2D cell (stable). */
static void sort_slabs(void *vctx, size_t begin, size_t end, int tid)
{
    sort_ctx *c = vctx;
    slab_grid *g = c->g;
    uint32_t *count = c->count[tid], *tmp = c->tmp[tid];
    size_t nc = ncells2d(g);
    for (size_t z = begin; z < end; z++) {
        uint32_t s0 = g->slab_start[z], s1 = g->slab_start[z + 1];
        if (s1 - s0 < 2) continue;
        memset(count, 0, (nc + 1) * sizeof *count);
        for (uint32_t k = s0; k < s1; k++) count[cell2d(g, c->pos + 3 * (size_t)g->atoms[k]) + 1]++;
        for (size_t q = 0; q < nc; q++) count[q + 1] += count[q];
        for (uint32_t k = s0; k < s1; k++) {
            uint32_t a = g->atoms[k];
            tmp[count[cell2d(g, c->pos + 3 * (size_t)a)]++] = a;
        }
        memcpy(g->atoms + s0, tmp, (s1 - s0) * sizeof *tmp);
    }
}

static int grid_build(slab_grid *g, const float *pos, size_t n, float cutoff, ms_error *err)
{
    memset(g, 0, sizeof *g);
    size_t nvalid = grid_size(g, pos, n, cutoff);
    if (nvalid == 0) return 0;
    size_t nz = (size_t)g->dim[2];
    g->slab_start = calloc(nz + 1, sizeof *g->slab_start);
    g->atoms = ms_alloc_array(nvalid, sizeof *g->atoms);
    if (!g->slab_start || !g->atoms) goto oom;
    /* Bucket by slab: counts become inclusive ends, a descending fill makes them starts. */
    for (size_t i = 0; i < n; i++)
        if (finite3(pos + 3 * i)) g->slab_start[cell_coord(g, pos + 3 * i, 2)]++;
    for (size_t z = 0; z < nz; z++) {
        g->max_slab = MS_MAX(g->max_slab, (size_t)g->slab_start[z]);
        if (z) g->slab_start[z] += g->slab_start[z - 1];
    }
    for (size_t i = n; i-- > 0;)
        if (finite3(pos + 3 * i)) g->atoms[--g->slab_start[cell_coord(g, pos + 3 * i, 2)]] = (uint32_t)i;
    g->slab_start[nz] = (uint32_t)nvalid;

    int nt = ms_threads_count();
    sort_ctx c = {.g = g, .pos = pos};
    c.count = calloc((size_t)nt, sizeof *c.count);
    c.tmp = calloc((size_t)nt, sizeof *c.tmp);
    int ok = c.count && c.tmp;
    for (int t = 0; ok && t < nt; t++) {
        c.count[t] = ms_alloc_array(ncells2d(g) + 1, sizeof **c.count);
        c.tmp[t] = ms_alloc_array(g->max_slab, sizeof **c.tmp);
        ok = c.count[t] && c.tmp[t];
    }
    if (ok) ms_parallel_for(nz, 1, sort_slabs, &c);
    for (int t = 0; t < nt; t++) {
        if (c.count) free(c.count[t]);
        if (c.tmp) free(c.tmp[t]);
    }
    free(c.count);
    free(c.tmp);
    if (ok) return 0;
oom:
    grid_free(g);
    ms_error_set(err, "out of memory for the bond search grid of %zu atoms", n);
    return -1;
}

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
    uint32_t *start_a, *start_b;  /* 2D cell starts of this slab and the next */
} pair_buf;

typedef struct search_ctx {
    const ms_molecule *m;
    const float *pos;
    const slab_grid *g;
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
    free(b->start_a);
    free(b->start_b);
}

/* 2D cell starts of slab z (its atoms are sorted by 2D cell). */
static void slab_starts(const slab_grid *g, const float *pos, size_t z, uint32_t *start)
{
    size_t nc = ncells2d(g);
    memset(start, 0, (nc + 1) * sizeof *start);
    if (z >= (size_t)g->dim[2]) return;
    uint32_t s0 = g->slab_start[z], s1 = g->slab_start[z + 1];
    for (uint32_t k = s0; k < s1; k++) start[cell2d(g, pos + 3 * (size_t)g->atoms[k]) + 1]++;
    start[0] = s0;
    for (size_t q = 0; q < nc; q++) start[q + 1] += start[q];
}

/* Neighbour cells of (x, y): in the same slab the forward half (itself and 4 others), in
 * the next slab all 9: every pair of cells is visited once. */
static const int same_slab[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};

static void search_pairs(search_ctx *c, pair_buf *buf, const uint32_t *sa, uint32_t a0,
                         uint32_t a1, const uint32_t *sb, size_t other, int same)
{
    const slab_grid *g = c->g;
    uint32_t b0 = sb[other], b1 = sb[other + 1];
    for (uint32_t ia = a0; ia < a1; ia++) {
        uint32_t i = g->atoms[ia];
        for (uint32_t jb = same ? ia + 1 : b0; jb < b1; jb++) {
            uint32_t j = g->atoms[jb];
            if (may_bond(c->m, i, j, c->pos)) push_pair(buf, i, j);
        }
    }
    (void)sa;
}

static void search_slabs(void *vctx, size_t begin, size_t end, int tid)
{
    search_ctx *c = vctx;
    const slab_grid *g = c->g;
    pair_buf *buf = &c->bufs[tid];
    int nx = g->dim[0], ny = g->dim[1];
    for (size_t z = begin; z < end; z++) {
        if (g->slab_start[z] == g->slab_start[z + 1]) continue;
        slab_starts(g, c->pos, z, buf->start_a);
        slab_starts(g, c->pos, z + 1, buf->start_b);
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++) {
                size_t cell = (size_t)y * (size_t)nx + (size_t)x;
                uint32_t a0 = buf->start_a[cell], a1 = buf->start_a[cell + 1];
                if (a0 == a1) continue;
                for (int s = 0; s < 5; s++) {
                    int ox = x + same_slab[s][0], oy = y + same_slab[s][1];
                    if (ox < 0 || oy < 0 || ox >= nx || oy >= ny) continue;
                    search_pairs(c, buf, buf->start_a, a0, a1, buf->start_a,
                                 (size_t)oy * (size_t)nx + (size_t)ox, s == 0);
                }
                if (z + 1 >= (size_t)g->dim[2]) continue;
                for (int oy = y - 1; oy <= y + 1; oy++)
                    for (int ox = x - 1; ox <= x + 1; ox++) {
                        if (ox < 0 || oy < 0 || ox >= nx || oy >= ny) continue;
                        search_pairs(c, buf, buf->start_a, a0, a1, buf->start_b,
                                     (size_t)oy * (size_t)nx + (size_t)ox, 0);
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
    slab_grid g;
    if (grid_build(&g, pos, n, 1.2f * rmax, err)) return -1;
    if (!g.atoms) return 0;

    int nt = ms_threads_count();
    search_ctx ctx = {.m = m, .pos = pos, .g = &g, .bufs = calloc((size_t)nt, sizeof(pair_buf))};
    int failed = ctx.bufs == NULL;
    for (int t = 0; !failed && t < nt; t++) {
        ctx.bufs[t].start_a = ms_alloc_array(ncells2d(&g) + 1, sizeof(uint32_t));
        ctx.bufs[t].start_b = ms_alloc_array(ncells2d(&g) + 1, sizeof(uint32_t));
        failed = !ctx.bufs[t].start_a || !ctx.bufs[t].start_b;
    }
    if (!failed) ms_parallel_for((size_t)g.dim[2], 1, search_slabs, &ctx);
    grid_free(&g);

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
