/* internal.h: what the files of src/pbc share and nothing else needs: floor and round
 * without a libm call (the scalar loops run them three times per atom and frame), the
 * lattice shift n0 A + n1 B + n2 C of a lower-triangular cell, runs of consecutive atoms
 * and the vectorised loops over them (kernels.c). */
#ifndef MS_PBC_INTERNAL_H
#define MS_PBC_INTERNAL_H

#include "pbc/pbc.h"

/* Fractional offsets this large (or NaN) leave an atom where it is. */
#define MS_PBC_HUGE 0x1p51

/* floor(x) for |x| < 2^51; 0 for anything else (NaN, huge), which leaves the atom alone. */
static inline double ms_pbc_floor(double x)
{
    if (!(x > -MS_PBC_HUGE && x < MS_PBC_HUGE)) return 0;
    long long i = (long long)x;
    return (double)(i - (x < (double)i));
}

static inline double ms_pbc_round(double x) { return ms_pbc_floor(x + 0.5); }

/* Fractional coordinates s of q (the cell's inverse is lower triangular too). */
static inline void ms_pbc_frac(const ms_pbc_cell *c, const double q[3], double s[3])
{
    s[0] = q[0] * c->inv[0][0] + q[1] * c->inv[1][0] + q[2] * c->inv[2][0];
    s[1] = q[1] * c->inv[1][1] + q[2] * c->inv[2][1];
    s[2] = q[2] * c->inv[2][2];
}

/* t = n0 A + n1 B + n2 C. */
static inline void ms_pbc_lattice(const ms_pbc_cell *c, const double n[3], double t[3])
{
    t[0] = n[0] * c->v[0][0] + n[1] * c->v[1][0] + n[2] * c->v[2][0];
    t[1] = n[1] * c->v[1][1] + n[2] * c->v[2][1];
    t[2] = n[2] * c->v[2][2];
}

/* Ascending atoms as runs of consecutive atoms, each at most maxlen long: run k is atoms
 * run[k][0] .. run[k][0] + run[k][1] - 1. */
typedef struct ms_pbc_runs {
    size_t n;
    uint32_t (*run)[2];
} ms_pbc_runs;

int ms_pbc_runs_make(const uint32_t *atoms, size_t n, size_t maxlen, ms_pbc_runs *r);

/* The loops over the n consecutive atoms at p (xyz floats), same rules as the scalar code:
 * wrap into the parallelepiped (or the brick Ax By Cz) whose lowest corner is origin, and
 * unwrap: each atom to the image nearest its position in prev. */
void ms_pbc_wrap_run(float *p, size_t n, const ms_pbc_cell *c, const double origin[3]);
void ms_pbc_wrap_run_brick(float *p, size_t n, const ms_pbc_cell *c, const double origin[3]);
void ms_pbc_unwrap_run(float *p, const float *prev, size_t n, const ms_pbc_cell *c);

#endif
