/* internal.h: helpers shared by the files of src/measure, not part of its public API: the
 * neighbour grid of its pair searches, a deterministic parallel reduction, and small
 * conversions. */
#ifndef MS_MEASURE_INTERNAL_H
#define MS_MEASURE_INTERNAL_H

#include "measure/measure.h"
#include "base/grid.h"

/* ---- neighbour grid (base/grid.h) over a set of atoms, cells at least `cutoff` wide and at
 * most about four per atom; atoms with non-finite coordinates are left out. */
static inline int ms_measure_grid(ms_grid *g, const float *pos, const uint32_t *atoms, size_t n,
                                  double cutoff, ms_error *err)
{
    ms_grid_points p = {pos, 3, atoms, n};
    ms_grid_spec spec = {cutoff, 4.0, 64.0, 1.26, 0};
    return ms_grid_build(g, &p, &spec, err);
}

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
