/* atomgrid.c: the spatial acceleration grid: atoms converted to grid units with their
 * Gaussian exponent factor and colour, bucket-sorted by cell (a stable counting sort on
 * all cores), so that the density loops find the atoms near any voxel in linear time. */
#include "config.h"
#include "surf/qsurf_impl.h"
#include "base/threads.h"

#include <stdlib.h>
#include <string.h>

/* Cells at least one cutoff wide (VMD: max(gausslim s maxrad, h)), coarsened when the box
 * is so sparse that the cell table would outgrow the atoms. */
void ms_qsurf_atomgrid_cells(const ms_qsurf_grid *g, int nc[3])
{
    double cell = MS_MAX(g->gausslim * g->radscale * g->maxrad, g->h);
    double limit = 4.0 * (double)g->natoms + 4096.0;
    for (int pass = 0; pass < 8; pass++) {
        double total = 1.0;
        for (int a = 0; a < 3; a++) {
            double k = (double)g->n[a] * g->h / cell;
            nc[a] = k < 1.0 ? 1 : (int)k;
            total *= nc[a];
        }
        if (total <= limit) break;
        cell *= cbrt(total / limit) * 1.01;
    }
}

static size_t ncells_of(const int nc[3])
{
    return (size_t)nc[0] * (size_t)nc[1] * (size_t)nc[2];
}

size_t ms_qsurf_atomgrid_bytes(const ms_qsurf_grid *g, int colored)
{
    int nc[3];
    ms_qsurf_atomgrid_cells(g, nc);
    size_t cells = ncells_of(nc) + 1, threads = (size_t)ms_threads_count();
    size_t scratch = threads * ms_qsurf_scratch_floats(g->n) * sizeof(float);
    return g->natoms * (colored ? 32 : 16) + cells * 4 * (threads + 1) + scratch;
}

typedef struct sort_ctx {
    const ms_qsurf_atoms *a;
    const ms_qsurf_grid *g;
    ms_qsurf_atomgrid *ag;
    uint32_t *slot;          /* per part and cell: count, then next destination */
    size_t ncells;
    int parts;
    float wfac, cfac;        /* exponent factor without 1/r^2; colour scale 1/iso */
} sort_ctx;

static int cell_index(const sort_ctx *c, const float *g3)
{
    const ms_qsurf_atomgrid *ag = c->ag;
    int cx = ms_qsurf_cell_of(g3[0], ag->cw[0], ag->nc[0]);
    int cy = ms_qsurf_cell_of(g3[1], ag->cw[1], ag->nc[1]);
    int cz = ms_qsurf_cell_of(g3[2], ag->cw[2], ag->nc[2]);
    return (cz * ag->nc[1] + cy) * ag->nc[0] + cx;
}

/* Atom k in grid units; 0 when it does not contribute. */
static int grid_coords(const sort_ctx *c, size_t k, float out[3], size_t *src)
{
    size_t i = ms_qsurf_atom_index(c->a, k);
    const float *p = c->a->pos + 3 * i;
    if (!ms_qsurf_atom_ok(p, c->a->radius[i])) return 0;
    for (int d = 0; d < 3; d++) out[d] = (p[d] - c->g->origin[d]) / c->g->h;
    *src = i;
    return 1;
}

static void part_range(const sort_ctx *c, size_t part, size_t *b, size_t *e)
{
    *b = c->a->n * part / (size_t)c->parts;
    *e = c->a->n * (part + 1) / (size_t)c->parts;
}

static void count_part(void *ctx, size_t begin, size_t end, int thread)
{
    sort_ctx *c = ctx;
    for (size_t part = begin; part < end; part++) {
        size_t b, e, src;
        uint32_t *slot = c->slot + part * c->ncells;
        part_range(c, part, &b, &e);
        for (size_t k = b; k < e; k++) {
            float g3[3];
            if (grid_coords(c, k, g3, &src)) slot[cell_index(c, g3)]++;
        }
    }
}

static void place_part(void *ctx, size_t begin, size_t end, int thread)
{
    sort_ctx *c = ctx;
    ms_qsurf_atomgrid *ag = c->ag;
    for (size_t part = begin; part < end; part++) {
        size_t b, e, src;
        uint32_t *slot = c->slot + part * c->ncells;
        part_range(c, part, &b, &e);
        for (size_t k = b; k < e; k++) {
            float g3[3];
            if (!grid_coords(c, k, g3, &src)) continue;
            size_t dst = slot[cell_index(c, g3)]++;
            float r = c->a->radius[src];
            float *o = ag->xyzw + 4 * dst;
            o[0] = g3[0], o[1] = g3[1], o[2] = g3[2];
            o[3] = c->wfac / (r * r);
            if (!ag->rgb) continue;
            const float *rgb = c->a->rgb + 3 * src;
            float *q = ag->rgb + 4 * dst;
            q[0] = rgb[0] * c->cfac, q[1] = rgb[1] * c->cfac, q[2] = rgb[2] * c->cfac;
            q[3] = 0.0f;
        }
    }
}

/* Turn per-part counts into destinations: cell by cell, part by part (a stable order). */
static void prefix(sort_ctx *c)
{
    uint32_t run = 0;
    for (size_t cell = 0; cell < c->ncells; cell++) {
        c->ag->cellstart[cell] = run;
        for (int p = 0; p < c->parts; p++) {
            uint32_t n = c->slot[(size_t)p * c->ncells + cell];
            c->slot[(size_t)p * c->ncells + cell] = run;
            run += n;
        }
    }
    c->ag->cellstart[c->ncells] = run;
}

static void setup(ms_qsurf_atomgrid *ag, const ms_qsurf_grid *g, sort_ctx *c)
{
    ms_qsurf_atomgrid_cells(g, ag->nc);
    for (int d = 0; d < 3; d++) ag->cw[d] = (float)g->n[d] / (float)ag->nc[d];
    float s = g->radscale;
    c->wfac = -MS_QSURF_LOG2E * g->h * g->h / (2.0f * s * s);
    c->cfac = 1.0f / g->isovalue;
    ag->elim = -g->gausslim * g->gausslim * MS_QSURF_LOG2E * 0.5f;
    /* A little slack so that rounding never leaves a contributing atom outside. */
    ag->cutmax = g->gausslim * s * g->maxrad / g->h * 1.001f + 1e-3f;
    c->ncells = ncells_of(ag->nc);
}

int ms_qsurf_atomgrid_build(const ms_qsurf_atoms *a, const ms_qsurf_grid *g,
                            ms_qsurf_atomgrid *ag, ms_error *err)
{
    sort_ctx c = {.a = a, .g = g, .ag = ag};
    memset(ag, 0, sizeof *ag);
    setup(ag, g, &c);
    c.parts = ms_threads_count();
    ag->n = g->natoms;
    ag->xyzw = ms_alloc_array(g->natoms, 4 * sizeof(float));
    ag->cellstart = ms_alloc_array(c.ncells + 1, sizeof(uint32_t));
    c.slot = ms_calloc_array(c.ncells * (size_t)c.parts, sizeof(uint32_t));
    if (a->rgb) ag->rgb = ms_alloc_array(g->natoms, 4 * sizeof(float));
    ag->scratch_n = ms_qsurf_scratch_floats(g->n);
    ag->scratch = ms_calloc_array(ag->scratch_n * (size_t)c.parts, sizeof(float));
    if (!ag->xyzw || !ag->cellstart || !c.slot || (a->rgb && !ag->rgb) || !ag->scratch ||
        g->natoms > UINT32_MAX) {
        free(c.slot);
        ms_qsurf_atomgrid_free(ag);
        ms_error_set(err, "out of memory for the atom grid of %zu atoms", g->natoms);
        return -1;
    }
    ms_parallel_for((size_t)c.parts, 1, count_part, &c);
    prefix(&c);
    ms_parallel_for((size_t)c.parts, 1, place_part, &c);
    free(c.slot);
    return 0;
}

void ms_qsurf_atomgrid_free(ms_qsurf_atomgrid *ag)
{
    free(ag->xyzw);
    free(ag->rgb);
    free(ag->cellstart);
    free(ag->scratch);
    memset(ag, 0, sizeof *ag);
}
