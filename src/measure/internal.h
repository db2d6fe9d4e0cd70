/* internal.h: helpers shared by the files of src/measure, not part of its public API: a
 * uniform cell grid for neighbour searches, a deterministic parallel reduction, and small
 * conversions. */
#ifndef MS_MEASURE_INTERNAL_H
#define MS_MEASURE_INTERNAL_H

#include "measure/measure.h"

/* ---- cell grid: cells at least `cutoff` wide over a set of atoms, so every neighbour of a
 * point within cutoff lies in the 27 cells around the point's own. Atoms with non-finite
 * coordinates are left out. */
typedef struct ms_cellgrid {
    double origin[3], cell;
    int dim[3];
    size_t ncells;
    uint32_t *start;       /* ncells + 1 offsets into atoms */
    uint32_t *atoms;       /* atom indices by cell, ascending inside a cell */
} ms_cellgrid;

int ms_cellgrid_build(ms_cellgrid *g, const float *pos, const uint32_t *atoms, size_t n,
                      double cutoff, ms_error *err);
void ms_cellgrid_free(ms_cellgrid *g);
/* The existing cells among the 27 around point p (none for a non-finite p); returns how
 * many were written to cells. */
int ms_cellgrid_around(const ms_cellgrid *g, const float p[3], size_t cells[27]);

/* ---- deterministic reduction: [0, n) is cut into fixed chunks, run in parallel; fn fills
 * acc (k doubles, zeroed beforehand) for its chunk. Returns the nchunks
 * accumulators one after another (malloc'd), so the caller combines them in a fixed order
 * whatever the thread schedule; NULL when memory runs out. */
typedef void (*ms_chunk_fn)(void *ctx, size_t begin, size_t end, double *acc);
double *ms_measure_chunks(size_t n, size_t k, ms_chunk_fn fn, void *ctx, size_t *nchunks);

static inline void ms_pos3(const float *pos, uint32_t i, double p[3])
{
    p[0] = pos[3 * (size_t)i];
    p[1] = pos[3 * (size_t)i + 1];
    p[2] = pos[3 * (size_t)i + 2];
}

static inline double ms_dist2f(const float *a, const float *b)
{
    double dx = (double)a[0] - b[0], dy = (double)a[1] - b[1], dz = (double)a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

/* Are atoms i and j bonded (their CSR entries are sorted)? */
int ms_measure_bonded(const ms_molecule *m, uint32_t i, uint32_t j);

#endif
