/* internal.h: what the files of src/pbc share and nothing else needs: floor and round
 * without a libm call (the loops run them three times per atom and frame), and the
 * lattice shift n0 A + n1 B + n2 C of a lower-triangular cell. */
#ifndef MS_PBC_INTERNAL_H
#define MS_PBC_INTERNAL_H

#include "pbc/pbc.h"

/* floor(x) for |x| < 2^62; 0 for anything else (NaN, huge), which leaves the atom alone. */
static inline double ms_pbc_floor(double x)
{
    if (!(x > -4e18 && x < 4e18)) return 0;
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

#endif
