/* grid.h: the one uniform cell grid behind every neighbour search (distance bonds, the
 * pairs of DynamicBonds and HBonds, `within`, measure's pair searches, DSSP's hydrogen
 * bonds). Points are counting-sorted into cubic cells at least the cutoff wide, so every
 * neighbour of a point within the cutoff lies in the 27 cells around the point's own; the
 * cell count is kept proportional to the point count, so a few points spread over a huge
 * box stay cheap. Points with non-finite coordinates are left out. The searches read the
 * cells as runs of the sorted items, in the order z, y, x (within a cell: ascending input
 * order), which is the order their results come out in. */
#ifndef MS_BASE_GRID_H
#define MS_BASE_GRID_H

#include "base/base.h"

#include <stddef.h>
#include <stdint.h>

/* The points: point k is xyz + stride * (ids ? ids[k] : k), and its item (what the grid
 * stores) is ids ? ids[k] : k. stride 0 means 3 (packed xyz). */
typedef struct ms_grid_points {
    const float *xyz;
    size_t stride;
    const uint32_t *ids;
    size_t n;
} ms_grid_points;

/* The shape: cells cutoff wide (1 when cutoff is not positive), grown by the factor grow
 * until there are at most per_point * n + extra cells. A search whose distance test must
 * never miss a pair at exactly the cutoff passes a hair more (cutoff * 1.000001). With
 * single set, a point's cell is computed in single precision (lowest corner and cell edge
 * rounded to float), as the pair search of the representations always has: it decides the
 * order the pairs come out in, which exported scenes show. */
typedef struct ms_grid_spec {
    double cutoff, per_point, extra, grow;
    int single;
} ms_grid_spec;

typedef struct ms_grid {
    double origin[3], cell;  /* the lowest corner of the points, the cell's edge */
    double top[3];           /* the highest corner of the points */
    int single;              /* cells computed in float, from these: */
    float origin_f[3], cell_f;
    long dim[3];
    size_t ncells;
    size_t n;                /* the finite points placed */
    uint32_t *start;         /* ncells + 1: cell c holds items[start[c] .. start[c + 1]) */
    uint32_t *items;         /* by cell (z, y, x major to minor), input order inside a cell */
} ms_grid;

/* A run of consecutive items: the cells x0..x1 of one row. */
typedef struct ms_grid_run {
    uint32_t begin, end;
} ms_grid_run;

/* 0, or -1 with err set (out of memory, too many points); g is zeroed first. */
int ms_grid_build(ms_grid *g, const ms_grid_points *p, const ms_grid_spec *spec, ms_error *err);
void ms_grid_free(ms_grid *g);

static inline size_t ms_grid_index(const ms_grid *g, long x, long y, long z)
{
    return ((size_t)z * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[0] + (size_t)x;
}

/* The cell coordinates of p, clamped into the grid (p finite). */
void ms_grid_coords(const ms_grid *g, const float p[3], long c[3]);

/* The items of the cells x0..x1 of row (y, z), coordinates inside the grid. */
static inline ms_grid_run ms_grid_row(const ms_grid *g, long x0, long x1, long y, long z)
{
    ms_grid_run r = {g->start[ms_grid_index(g, x0, y, z)], g->start[ms_grid_index(g, x1, y, z) + 1]};
    return r;
}

/* The block of the 27 cells around p that lie in the grid, lo[k]..hi[k] along each axis;
 * 0 when p is not finite or lies more than a cell outside the grid (a single-precision
 * grid takes p's clamped cell: it is meant for its own points), else 1. */
int ms_grid_block(const ms_grid *g, const float p[3], long lo[3], long hi[3]);

/* The items in ms_grid_block's cells as up to 9 runs (its rows), in the order z, y, x.
 * Returns the number of runs. */
int ms_grid_near(const ms_grid *g, const float p[3], ms_grid_run runs[9]);

/* The forward half of the cells around cell (x, y, z), the cell itself left out: with every
 * cell's own pairs, each pair of neighbouring cells is visited exactly once. Up to 5 runs;
 * returns their number. */
int ms_grid_forward(const ms_grid *g, long x, long y, long z, ms_grid_run runs[5]);

#endif
