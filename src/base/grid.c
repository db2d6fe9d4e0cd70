/* grid.c: the uniform cell grid of grid.h: its shape, the counting sort of the points into
 * cells, and the neighbour cells of a point or of a cell as runs of the sorted items. */
#include "config.h"
#include "base/grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const float *point(const ms_grid_points *p, size_t k)
{
    size_t at = p->ids ? (size_t)p->ids[k] : k;
    return p->xyz + (p->stride ? p->stride : 3) * at;
}

static int finite3(const float *q)
{
    return isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2]);
}

/* Bounding box of the finite points; returns how many there are (box 0..0 when none). */
static size_t bounds(const ms_grid_points *p, double lo[3], double hi[3])
{
    size_t valid = 0;
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        const float *q = point(p, i);
        if (!finite3(q)) continue;
        for (int k = 0; k < 3; k++) {
            if (q[k] < lo[k]) lo[k] = q[k];
            if (q[k] > hi[k]) hi[k] = q[k];
        }
        valid++;
    }
    if (!valid)
        for (int k = 0; k < 3; k++) lo[k] = hi[k] = 0.0;
    return valid;
}

static void shape(ms_grid *g, const double lo[3], const double hi[3], const ms_grid_spec *s)
{
    double cell = s->cutoff > 0 ? s->cutoff : 1.0;
    double limit = s->per_point * (double)g->n + s->extra;
    for (;;) {
        double cells = 1.0;
        for (int k = 0; k < 3; k++) cells *= floor((hi[k] - lo[k]) / cell) + 1.0;
        if (cells <= limit) break;
        cell *= s->grow;
    }
    g->cell = cell;
    g->cell_f = (float)cell;
    g->single = s->single;
    g->ncells = 1;
    for (int k = 0; k < 3; k++) {
        g->origin[k] = lo[k];
        g->top[k] = hi[k];
        g->origin_f[k] = (float)lo[k];
        g->dim[k] = (long)floor((hi[k] - lo[k]) / cell) + 1;
        g->ncells *= (size_t)g->dim[k];
    }
}

static inline void coords(const ms_grid *g, const float p[3], long c[3])
{
    for (int k = 0; k < 3; k++) {
        double v = g->single ? (double)(int)((p[k] - g->origin_f[k]) / g->cell_f)
                             : floor(((double)p[k] - g->origin[k]) / g->cell);
        c[k] = v < 0 ? 0 : v >= (double)g->dim[k] ? g->dim[k] - 1 : (long)v;
    }
}

void ms_grid_coords(const ms_grid *g, const float p[3], long c[3]) { coords(g, p, c); }

/* The cell of finite point q. */
static inline size_t cell_of(const ms_grid *g, const float *q)
{
    long c[3];
    coords(g, q, c);
    return ms_grid_index(g, c[0], c[1], c[2]);
}

/* Counting sort, stable: ascending inputs stay ascending inside a cell. */
static int fill(ms_grid *g, const ms_grid_points *p)
{
    uint32_t *which = ms_alloc_array(p->n ? p->n : 1, sizeof *which);   /* cell, or none */
    g->start = ms_calloc_array(g->ncells + 2, sizeof *g->start);
    g->items = ms_alloc_array(g->n ? g->n : 1, sizeof *g->items);
    if (!which || !g->start || !g->items) {
        free(which);
        return -1;
    }
    for (size_t i = 0; i < p->n; i++) {
        const float *q = point(p, i);
        which[i] = finite3(q) ? (uint32_t)cell_of(g, q) : UINT32_MAX;
        if (which[i] != UINT32_MAX) g->start[which[i] + 2]++;
    }
    for (size_t c = 2; c < g->ncells + 2; c++) g->start[c] += g->start[c - 1];
    /* start[c + 1] is cell c's fill cursor; filled, it is cell c's end */
    for (size_t i = 0; i < p->n; i++)
        if (which[i] != UINT32_MAX)
            g->items[g->start[which[i] + 1]++] = p->ids ? p->ids[i] : (uint32_t)i;
    free(which);
    return 0;
}

int ms_grid_build(ms_grid *g, const ms_grid_points *p, const ms_grid_spec *spec, ms_error *err)
{
    double lo[3], hi[3];
    memset(g, 0, sizeof *g);
    if (p->n > UINT32_MAX - 1) {
        ms_error_set(err, "too many points for the neighbour grid (%zu)", p->n);
        return -1;
    }
    g->n = bounds(p, lo, hi);
    shape(g, lo, hi, spec);
    if (fill(g, p)) {
        ms_grid_free(g);
        ms_error_set(err, "out of memory for the neighbour grid of %zu points", p->n);
        return -1;
    }
    return 0;
}

void ms_grid_free(ms_grid *g)
{
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}

int ms_grid_block(const ms_grid *g, const float p[3], long lo[3], long hi[3])
{
    long c[3];
    for (int k = 0; k < 3; k++) {
        if (!isfinite(p[k])) return 0;
        double v = floor(((double)p[k] - g->origin[k]) / g->cell);
        if (v < -1.0 || v > (double)g->dim[k]) return 0;   /* more than a cell outside */
        c[k] = (long)v;
    }
    if (g->single) coords(g, p, c);
    for (int k = 0; k < 3; k++) {
        lo[k] = MS_MAX(c[k] - 1, 0);
        hi[k] = MS_MIN(c[k] + 1, g->dim[k] - 1);
        if (lo[k] > hi[k]) return 0;
    }
    return 1;
}

int ms_grid_near(const ms_grid *g, const float p[3], ms_grid_run runs[9])
{
    long lo[3], hi[3];
    int n = 0;
    if (!ms_grid_block(g, p, lo, hi)) return 0;
    for (long z = lo[2]; z <= hi[2]; z++)
        for (long y = lo[1]; y <= hi[1]; y++) runs[n++] = ms_grid_row(g, lo[0], hi[0], y, z);
    return n;
}

int ms_grid_forward(const ms_grid *g, long x, long y, long z, ms_grid_run runs[5])
{
    long x0 = MS_MAX(x - 1, 0), x1 = MS_MIN(x + 1, g->dim[0] - 1);
    int n = 0;
    if (x + 1 < g->dim[0]) runs[n++] = ms_grid_row(g, x + 1, x + 1, y, z);
    if (y + 1 < g->dim[1]) runs[n++] = ms_grid_row(g, x0, x1, y + 1, z);
    if (z + 1 < g->dim[2])
        for (long oy = MS_MAX(y - 1, 0); oy <= MS_MIN(y + 1, g->dim[1] - 1); oy++)
            runs[n++] = ms_grid_row(g, x0, x1, oy, z + 1);
    return n;
}
