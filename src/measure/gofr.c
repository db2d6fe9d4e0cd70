/* gofr.c: radial distribution functions g(r), frame by frame, normalised as VMD's
 * `measure gofr` does (see ms_gofr_add_frame). Pair distances come from a cell grid: a plain
 * one without periodic boundaries, or one in fractional coordinates of the unit cell with
 * periodic boundaries, where each of the 27 neighbour cells is visited as a periodic image
 * (so small cells, where neighbours wrap onto the same cell, still count each image once).
 * Orthorhombic cells use VMD's minimum-image convention up to sqrt(1/2) of the shortest
 * side; triclinic cells are supported up to half the shortest cell width, where an image
 * within reach is the only one. */
#include "config.h"
#include "measure/internal.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_BINS 10000000

struct ms_gofr {
    double delta;
    size_t nbins;
    int usepbc;
    double *sum_g, *sum_n, *sum_h;             /* sums over frames */
    double *r, *avg_g, *avg_n, *avg_h;         /* what ms_gofr_get hands out */
    long total, skipped, done;
};

ms_gofr *ms_gofr_new(double delta, double rmax, int usepbc, ms_error *err)
{
    if (!(delta > 0) || !(rmax > 0) || !isfinite(delta) || !isfinite(rmax) ||
        rmax / delta + 1.0 > MAX_BINS) {
        ms_error_set(err, "need delta > 0 and rmax > 0 with at most %d bins", MAX_BINS);
        return NULL;
    }
    ms_gofr *g = calloc(1, sizeof *g);
    if (!g) goto oom;
    g->delta = delta;
    g->nbins = (size_t)(rmax / delta + 1.0);
    g->usepbc = usepbc;
    double **arrays[] = {&g->sum_g, &g->sum_n, &g->sum_h, &g->r, &g->avg_g, &g->avg_n, &g->avg_h};
    for (size_t k = 0; k < MS_COUNTOF(arrays); k++)
        if (!(*arrays[k] = ms_calloc_array(g->nbins, sizeof(double)))) goto oom;
    for (size_t i = 0; i < g->nbins; i++) g->r[i] = delta * ((double)i + 0.5);
    return g;
oom:
    ms_gofr_free(g);
    ms_error_set(err, "out of memory for the g(r) histogram");
    return NULL;
}

void ms_gofr_free(ms_gofr *g)
{
    if (!g) return;
    free(g->sum_g), free(g->sum_n), free(g->sum_h);
    free(g->r), free(g->avg_g), free(g->avg_n), free(g->avg_h);
    free(g);
}

void ms_gofr_get(ms_gofr *g, ms_gofr_result *res)
{
    double norm = g->total ? 1.0 / (double)g->total : 0.0;
    for (size_t i = 0; i < g->nbins; i++) {
        g->avg_g[i] = g->sum_g[i] * norm;
        g->avg_n[i] = g->sum_n[i] * norm;
        g->avg_h[i] = g->sum_h[i] * norm;
    }
    res->nbins = g->nbins;
    res->r = g->r;
    res->gofr = g->avg_g;
    res->numint = g->avg_n;
    res->hist = g->avg_h;
    res->frames_total = g->total;
    res->frames_skipped = g->skipped;
    res->frames_done = g->done;
}

/* ---------------------------------------------------------------- the unit cell */

typedef struct cell_geom {
    double H[9], Hinv[9];     /* lattice vectors as columns, and the inverse */
    double volume, width[3];  /* perpendicular widths across the three pairs of faces */
    int ortho;
} cell_geom;

static void mat3_inverse(const double m[9], double det, double inv[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            inv[3 * i + j] = (m[3 * a + c] * m[3 * b + d] - m[3 * a + d] * m[3 * b + c]) / det;
        }
}

/* The cell of a frame: a b c alpha beta gamma, in VMD's orientation (a along x, b in xy). */
static int cell_from_frame(const ms_frame *f, cell_geom *cg, ms_error *err)
{
    double a = f->cell[0], b = f->cell[1], c = f->cell[2], d2r = M_PI / 180.0;
    double ca = cos(f->cell[3] * d2r), cb = cos(f->cell[4] * d2r), cc = cos(f->cell[5] * d2r);
    double sc = sin(f->cell[5] * d2r), cy = (ca - cb * cc) / sc;
    double cz2 = 1.0 - cb * cb - cy * cy;
    if (!(fabs(a * b * c) >= 0.0001) || !(fabs(sc) > 1e-6) || !(cz2 > 1e-12)) {
        ms_error_set(err, "the unit cell {%g %g %g %g %g %g} has no volume",
                     f->cell[0], f->cell[1], f->cell[2], f->cell[3], f->cell[4], f->cell[5]);
        return -1;
    }
    double H[9] = {a, b * cc, c * cb, 0, b * sc, c * cy, 0, 0, c * sqrt(cz2)};
    memcpy(cg->H, H, sizeof H);
    cg->volume = H[0] * H[4] * H[8];
    mat3_inverse(H, cg->volume, cg->Hinv);
    for (int k = 0; k < 3; k++) {   /* width_k = V / |face k|, the reciprocal row's inverse */
        const double *r = cg->Hinv + 3 * k;
        cg->width[k] = 1.0 / sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    }
    cg->ortho = fabs(f->cell[3] - 90) < 1e-3 && fabs(f->cell[4] - 90) < 1e-3 &&
                fabs(f->cell[5] - 90) < 1e-3;
    if (cg->ortho) cg->volume = a * b * c;
    return 0;
}

/* Bins of this frame that get normalised, as VMD: up to sqrt(1/2) of the shortest side in an
 * orthorhombic cell (with the cap corrections below), up to half the shortest width in a
 * triclinic one, all of them without periodic boundaries. */
static size_t usable_bins(const ms_gofr *g, const cell_geom *cg)
{
    size_t h;
    if (!g->usepbc) return g->nbins;
    if (cg->ortho) {
        double side = fmin(cg->H[0], fmin(cg->H[4], cg->H[8]));
        h = (size_t)(sqrt(0.5) * side / g->delta) + 1;
    } else {
        double w = fmin(cg->width[0], fmin(cg->width[1], cg->width[2]));
        h = (size_t)(0.5 * w / g->delta);
    }
    return h < g->nbins ? h : g->nbins;
}

/* ---------------------------------------------------------------- the periodic grid */

typedef struct pgrid {
    const cell_geom *cg;
    int n[3];                 /* cells along each lattice vector */
    size_t ncells;
    uint32_t *start, *items;  /* items: positions in the b list, by cell */
    double *wb;               /* wrapped positions of the b atoms */
} pgrid;

/* Wrap a point into the cell: its wrapped Cartesian position and its grid cell. */
static void wrap(const pgrid *pg, const float *x, double w[3], int c[3])
{
    const double *Hi = pg->cg->Hinv, *H = pg->cg->H;
    double s[3];
    for (int k = 0; k < 3; k++) {
        s[k] = Hi[3 * k] * x[0] + Hi[3 * k + 1] * x[1] + Hi[3 * k + 2] * x[2];
        s[k] -= floor(s[k]);
        if (!(s[k] < 1.0) || !(s[k] >= 0.0)) s[k] = 0.0;   /* rounding, or not finite */
        c[k] = (int)(s[k] * pg->n[k]);
        if (c[k] >= pg->n[k]) c[k] = pg->n[k] - 1;
    }
    for (int k = 0; k < 3; k++) w[k] = H[3 * k] * s[0] + H[3 * k + 1] * s[1] + H[3 * k + 2] * s[2];
}

/* Cells at least rc wide across each pair of faces, and not many more than the atoms. */
static void pgrid_dims(pgrid *pg, double rc, size_t natoms)
{
    double limit = 4.0 * (double)natoms + 64.0;
    for (int k = 0; k < 3; k++) {
        double n = floor(pg->cg->width[k] / rc);
        pg->n[k] = n < 1 ? 1 : n > 1024 ? 1024 : (int)n;
    }
    while ((double)pg->n[0] * pg->n[1] * pg->n[2] > limit) {
        int k = pg->n[0] >= pg->n[1] && pg->n[0] >= pg->n[2] ? 0 : pg->n[1] >= pg->n[2] ? 1 : 2;
        pg->n[k] = pg->n[k] / 2 > 1 ? pg->n[k] / 2 : 1;
    }
    pg->ncells = (size_t)pg->n[0] * (size_t)pg->n[1] * (size_t)pg->n[2];
}

static int pgrid_build(pgrid *pg, const float *pos, const uint32_t *b, size_t nb, double rc)
{
    pgrid_dims(pg, rc, nb);
    uint32_t *cellof = ms_alloc_array(nb, sizeof *cellof), *next = NULL;
    pg->start = ms_calloc_array(pg->ncells + 1, sizeof *pg->start);
    pg->items = ms_alloc_array(nb, sizeof *pg->items);
    pg->wb = ms_alloc_array(nb, 3 * sizeof *pg->wb);
    if (!cellof || !pg->start || !pg->items || !pg->wb) goto fail;
    for (size_t j = 0; j < nb; j++) {
        int c[3];
        wrap(pg, pos + 3 * (size_t)b[j], pg->wb + 3 * j, c);
        cellof[j] = (uint32_t)(((size_t)c[2] * pg->n[1] + c[1]) * pg->n[0] + c[0]);
        pg->start[cellof[j] + 1]++;
    }
    for (size_t c = 0; c < pg->ncells; c++) pg->start[c + 1] += pg->start[c];
    if (!(next = ms_alloc_array(pg->ncells, sizeof *next))) goto fail;
    memcpy(next, pg->start, pg->ncells * sizeof *next);
    for (size_t j = 0; j < nb; j++) pg->items[next[cellof[j]]++] = (uint32_t)j;
    free(next);
    free(cellof);
    return 0;
fail:
    free(cellof);
    return -1;
}

static void pgrid_free(pgrid *pg)
{
    free(pg->start);
    free(pg->items);
    free(pg->wb);
}

/* ---------------------------------------------------------------- pair counting */

typedef struct count_ctx {
    const ms_gofr *g;
    const float *pos;
    const uint32_t *a, *b;
    size_t hmax;              /* bins counted */
    double rc2;               /* (hmax delta)^2 */
    const pgrid *pg;          /* periodic, or */
    const ms_grid *grid;  /* plain */
    uint64_t *hist;           /* one histogram per thread */
} count_ctx;

static void count(const count_ctx *c, double d2, uint64_t *hist)
{
    if (d2 >= c->rc2) return;
    size_t bin = (size_t)(sqrt(d2) / c->g->delta);
    if (bin < c->hmax) hist[bin]++;
}

/* Is the displacement inside VMD's minimum-image box [-L/2, L/2) (orthorhombic only)? */
static int min_image(const cell_geom *cg, const double d[3])
{
    for (int k = 0; k < 3; k++) {
        double half = 0.5 * cg->H[4 * k];
        if (d[k] < -half || d[k] >= half) return 0;
    }
    return 1;
}

/* Atom i of a against the images of the b atoms in the 27 cells around it. */
static void count_periodic(const count_ctx *c, uint32_t i, uint64_t *hist)
{
    const pgrid *pg = c->pg;
    const double *H = pg->cg->H;
    double wi[3];
    int ci[3];
    wrap(pg, c->pos + 3 * (size_t)i, wi, ci);
    for (int o = 0; o < 27; o++) {
        int cell[3], shift[3], off[3] = {o % 3 - 1, o / 3 % 3 - 1, o / 9 - 1};
        for (int k = 0; k < 3; k++) {
            int v = ci[k] + off[k];
            shift[k] = v < 0 ? -1 : v >= pg->n[k] ? 1 : 0;
            cell[k] = v - shift[k] * pg->n[k];
        }
        double sv[3];
        for (int k = 0; k < 3; k++)
            sv[k] = H[3 * k] * shift[0] + H[3 * k + 1] * shift[1] + H[3 * k + 2] * shift[2];
        size_t cc = ((size_t)cell[2] * pg->n[1] + cell[1]) * pg->n[0] + cell[0];
        int same_image = !shift[0] && !shift[1] && !shift[2];
        for (uint32_t q = pg->start[cc]; q < pg->start[cc + 1]; q++) {
            uint32_t j = pg->items[q];
            if (same_image && c->b[j] == i) continue;       /* an atom in both sets */
            double d[3];
            for (int k = 0; k < 3; k++) d[k] = pg->wb[3 * j + k] + sv[k] - wi[k];
            if (pg->cg->ortho && !min_image(pg->cg, d)) continue;
            count(c, d[0] * d[0] + d[1] * d[1] + d[2] * d[2], hist);
        }
    }
}

static void count_plain(const count_ctx *c, uint32_t i, uint64_t *hist)
{
    ms_grid_run runs[9];
    const float *p = c->pos + 3 * (size_t)i;
    int nr = ms_grid_near(c->grid, p, runs);
    for (int k = 0; k < nr; k++)
        for (uint32_t q = runs[k].begin; q < runs[k].end; q++) {
            uint32_t j = c->grid->items[q];
            if (j != i) count(c, ms_dist2f(p, c->pos + 3 * (size_t)j), hist);
        }
}

static void count_range(void *vctx, size_t begin, size_t end, int thread)
{
    const count_ctx *c = vctx;
    uint64_t *hist = c->hist + (size_t)thread * c->hmax;
    for (size_t k = begin; k < end; k++) {
        if (c->pg) count_periodic(c, c->a[k], hist);
        else count_plain(c, c->a[k], hist);
    }
}

/* Histogram of this frame's pair distances into hist (hmax bins). */
static int histogram(const ms_gofr *g, count_ctx *c, const cell_geom *cg, size_t na, size_t nb,
                     uint64_t *hist, ms_error *err)
{
    int nt = ms_threads_count(), rc = -1;
    pgrid pg = {.cg = cg};
    ms_grid grid = {0};
    c->hist = ms_calloc_array((size_t)nt * c->hmax, sizeof *c->hist);
    if (!c->hist) ms_error_set(err, "out of memory for g(r) histograms");
    else if (g->usepbc && pgrid_build(&pg, c->pos, c->b, nb, sqrt(c->rc2)))
        ms_error_set(err, "out of memory for the periodic grid of %zu atoms", nb);
    else if (!g->usepbc && ms_measure_grid(&grid, c->pos, c->b, nb, sqrt(c->rc2), err)) {
        /* err set */
    } else {
        c->pg = g->usepbc ? &pg : NULL;
        c->grid = g->usepbc ? NULL : &grid;
        ms_parallel_for(na, 64, count_range, c);
        for (int t = 0; t < nt; t++)
            for (size_t i = 0; i < c->hmax; i++) hist[i] += c->hist[(size_t)t * c->hmax + i];
        rc = 0;
    }
    free(c->hist);
    pgrid_free(&pg);
    ms_grid_free(&grid);
    return rc;
}

/* Volume of the cap of a sphere of radius r beyond a plane at distance h from its centre. */
static double cap_volume(double r, double h)
{
    return M_PI / 3.0 * (r - h) * (r - h) * (2.0 * r + h);
}

/* Volume of the shell of bin i, without the parts beyond the faces of an orthorhombic cell
 * (between half the side and sqrt(1/2) of it, the minimum-image sphere is cut by them). */
static double shell_volume(const ms_gofr *g, const cell_geom *cg, size_t i)
{
    double rin = g->delta * (double)i, rout = g->delta * (double)(i + 1);
    double v = 4.0 / 3.0 * M_PI * (rout * rout * rout - rin * rin * rin);
    if (!g->usepbc || !cg->ortho) return v;
    for (int k = 0; k < 3; k++) {
        double half = 0.5 * cg->H[4 * k];
        if (rout > half) v -= 2.0 * cap_volume(rout, half);
        if (rin > half) v += 2.0 * cap_volume(rin, half);
    }
    return v;
}

/* VMD's normalisation: g = hist * pair_density / shell volume with pair_density = V / (na nb
 * - duplicates) (or 30 A^3 per atom of a without periodic boundaries); numint = running
 * sum of hist / na. */
static void accumulate(ms_gofr *g, const cell_geom *cg, const uint64_t *hist, size_t hmax,
                       size_t na, size_t nb, size_t dup)
{
    double pairs = (double)na * (double)nb - (double)dup;
    double volume = g->usepbc ? cg->volume : 30.0 * (double)na;
    double density = pairs > 0 ? volume / pairs : 0.0, all = 0.0;
    for (size_t i = 0; i < hmax; i++) {
        double h = (double)hist[i];
        g->sum_g[i] += density / shell_volume(g, cg, i) * h;
        all += h;
        g->sum_n[i] += all / (double)na;
        g->sum_h[i] += h;
    }
}

/* Atoms in both ascending lists. */
static size_t common(const uint32_t *a, size_t na, const uint32_t *b, size_t nb)
{
    size_t i = 0, j = 0, n = 0;
    while (i < na && j < nb) {
        if (a[i] == b[j]) n++, i++, j++;
        else if (a[i] < b[j]) i++;
        else j++;
    }
    return n;
}

int ms_gofr_add_frame(ms_gofr *g, const ms_molecule *m, size_t frame, const uint32_t *a,
                      size_t na, const uint32_t *b, size_t nb, ms_error *err)
{
    cell_geom cg = {.ortho = 1};
    if (frame >= m->nframes) {
        ms_error_set(err, "molecule %d has no frame %zu", m->id, frame);
        return -1;
    }
    if (g->usepbc && cell_from_frame(&m->frames[frame], &cg, err)) {
        ms_error_prefix(err, "frame %zu", frame);
        return -1;
    }
    g->total++;
    if (na == 0 || nb == 0) {
        g->skipped++;
        return 0;
    }
    const float *pos = ms_mol_frame_pos(m, frame, err);
    if (!pos) return -1;
    size_t hmax = usable_bins(g, &cg);
    uint64_t *hist = ms_calloc_array(hmax, sizeof *hist);
    count_ctx c = {.g = g, .pos = pos, .a = a, .b = b, .hmax = hmax,
                   .rc2 = (double)hmax * g->delta * (double)hmax * g->delta};
    if (!hist || (hmax && histogram(g, &c, &cg, na, nb, hist, err))) {
        if (!hist) ms_error_set(err, "out of memory for g(r)");
        free(hist);
        g->total--;
        return -1;
    }
    accumulate(g, &cg, hist, hmax, na, nb, common(a, na, b, nb));
    free(hist);
    g->done++;
    return 0;
}
