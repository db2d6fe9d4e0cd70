/* grid.c: the uniform cell grid behind the pair searches of src/measure (contacts, hydrogen
 * bonds, surface neighbours): atoms counting-sorted into cells at least the cutoff wide, with
 * the cell count kept proportional to the atom count so sparse systems stay cheap. */
#include "config.h"
#include "measure/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Bounding box of the finite atoms; returns how many there are. */
static size_t bounds(const float *pos, const uint32_t *atoms, size_t n, double lo[3],
                     double hi[3])
{
    size_t valid = 0;
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        const float *p = pos + 3 * (size_t)atoms[i];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        for (int k = 0; k < 3; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
        valid++;
    }
    return valid;
}

/* Cell size: at least the cutoff, and coarse enough that there are at most about four cells
 * per atom (so a few atoms spread over a huge box do not need a huge grid). */
static void choose_cells(ms_cellgrid *g, const double lo[3], const double hi[3], size_t valid,
                         double cutoff)
{
    double cell = cutoff > 0 ? cutoff : 1.0, limit = 4.0 * (double)valid + 64.0;
    for (;;) {
        double cells = 1.0;
        for (int k = 0; k < 3; k++) cells *= floor((hi[k] - lo[k]) / cell) + 1.0;
        if (cells <= limit) break;
        cell *= 1.26;
    }
    g->cell = cell;
    g->ncells = 1;
    for (int k = 0; k < 3; k++) {
        g->origin[k] = lo[k];
        g->dim[k] = (int)floor((hi[k] - lo[k]) / cell) + 1;
        g->ncells *= (size_t)g->dim[k];
    }
}

static size_t cell_of(const ms_cellgrid *g, const float *p)
{
    size_t c[3];
    for (int k = 0; k < 3; k++) {
        long v = (long)((p[k] - g->origin[k]) / g->cell);
        c[k] = v < 0 ? 0 : v >= g->dim[k] ? (size_t)g->dim[k] - 1 : (size_t)v;
    }
    return (c[2] * (size_t)g->dim[1] + c[1]) * (size_t)g->dim[0] + c[0];
}

static int fill(ms_cellgrid *g, const float *pos, const uint32_t *atoms, size_t n)
{
    uint32_t *which = ms_alloc_array(n, sizeof *which), *next = NULL;
    g->start = calloc(g->ncells + 1, sizeof *g->start);
    if (!which || !g->start) goto fail;
    for (size_t i = 0; i < n; i++) {
        const float *p = pos + 3 * (size_t)atoms[i];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            which[i] = UINT32_MAX;
            continue;
        }
        which[i] = (uint32_t)cell_of(g, p);
        g->start[which[i] + 1]++;
    }
    for (size_t c = 0; c < g->ncells; c++) g->start[c + 1] += g->start[c];
    next = ms_alloc_array(g->ncells, sizeof *next);
    g->atoms = ms_alloc_array(g->start[g->ncells], sizeof *g->atoms);
    if (!next || !g->atoms) goto fail;
    memcpy(next, g->start, g->ncells * sizeof *next);
    for (size_t i = 0; i < n; i++)   /* stable: ascending indices stay ascending */
        if (which[i] != UINT32_MAX) g->atoms[next[which[i]]++] = atoms[i];
    free(next);
    free(which);
    return 0;
fail:
    free(next);
    free(which);
    return -1;
}

int ms_cellgrid_build(ms_cellgrid *g, const float *pos, const uint32_t *atoms, size_t n,
                      double cutoff, ms_error *err)
{
    double lo[3], hi[3];
    memset(g, 0, sizeof *g);
    if (n > UINT32_MAX - 1) {
        ms_error_set(err, "too many atoms for the neighbour grid (%zu)", n);
        return -1;
    }
    size_t valid = bounds(pos, atoms, n, lo, hi);
    if (valid == 0) {
        for (int k = 0; k < 3; k++) lo[k] = hi[k] = 0.0;
    }
    choose_cells(g, lo, hi, valid, cutoff);
    if (fill(g, pos, atoms, n)) {
        ms_cellgrid_free(g);
        ms_error_set(err, "out of memory for the neighbour grid of %zu atoms", n);
        return -1;
    }
    return 0;
}

void ms_cellgrid_free(ms_cellgrid *g)
{
    free(g->start);
    free(g->atoms);
    memset(g, 0, sizeof *g);
}

int ms_cellgrid_around(const ms_cellgrid *g, const float p[3], size_t cells[27])
{
    long c[3];
    for (int k = 0; k < 3; k++) {
        if (!isfinite(p[k])) return 0;
        double v = floor((p[k] - g->origin[k]) / g->cell);
        if (v < -1.0 || v > (double)g->dim[k]) return 0;   /* more than a cell outside */
        c[k] = (long)v;
    }
    int n = 0;
    for (long z = c[2] - 1; z <= c[2] + 1; z++) {
        if (z < 0 || z >= g->dim[2]) continue;
        for (long y = c[1] - 1; y <= c[1] + 1; y++) {
            if (y < 0 || y >= g->dim[1]) continue;
            for (long x = c[0] - 1; x <= c[0] + 1; x++)
                if (x >= 0 && x < g->dim[0])
                    cells[n++] = ((size_t)z * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[0] + (size_t)x;
        }
    }
    return n;
}
