/* kernels.c: the per-atom loops of `pbc wrap` and `pbc unwrap` over runs of consecutive
 * atoms, vectorised. Atoms are taken BLOCK at a time out of the interleaved xyz floats into
 * double-precision arrays (exact), moved there by the same double-precision rule as the
 * scalar code (fractional coordinates by the inverse cell, floor, lattice vector back), and
 * written back only when an atom of the block moved. The loops carry no branches, so the
 * compiler vectorises them; where GCC and glibc allow it each kernel is built three times
 * (AVX-512, AVX2, the baseline) and the best the CPU runs is picked when the program loads.
 * All clones compute the same numbers: no fused multiply-add, floor is exact in each. */
#include "config.h"
#include "pbc/internal.h"

#include <math.h>
#include <string.h>

/* Comparisons inside the loops must not count as possible traps, or GCC will not turn
 * the selects into vector blends (values are unaffected: nothing is reassociated). */
#pragma GCC optimize("no-trapping-math")

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__) \
    && __GNUC__ >= 9
#define MS_PBC_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MS_PBC_CLONES
#endif

enum { BLOCK = 64 };

/* The helpers are inlined into each clone, where the calls' constants make them branch-free. */
#define KINLINE static inline __attribute__((always_inline))

/* floor, or 0 for NaN and |x| >= 2^51 (such an atom is left where it is); +0, never -0,
 * so that an atom that does not move gets a zero shift and keeps its bits. */
KINLINE double kfloor(double x)
{
    return (fabs(x) < MS_PBC_HUGE ? floor(x) : 0.0) + 0.0;
}

/* A block of atoms, coordinates apart: x[i], x[BLOCK + i], x[2 BLOCK + i]. */
typedef double block[3 * BLOCK];

/* Loops of a constant BLOCK trips (what -O2 vectorises); the last block of a run is
 * padded with zeros, which compute harmlessly and are not stored. */
KINLINE void load(const float *restrict p, size_t m, double *restrict b)
{
    if (m == BLOCK) {
        for (size_t i = 0; i < BLOCK; i++)
            b[i] = p[3 * i], b[BLOCK + i] = p[3 * i + 1], b[2 * BLOCK + i] = p[3 * i + 2];
        return;
    }
    for (size_t i = 0; i < BLOCK; i++) b[i] = b[BLOCK + i] = b[2 * BLOCK + i] = 0;
    for (size_t i = 0; i < m; i++) b[i] = p[3 * i], b[BLOCK + i] = p[3 * i + 1], b[2 * BLOCK + i] = p[3 * i + 2];
}

KINLINE void store(float *restrict p, size_t m, const double *restrict b)
{
    if (m == BLOCK) {
        for (size_t i = 0; i < BLOCK; i++)
            p[3 * i] = (float)b[i], p[3 * i + 1] = (float)b[BLOCK + i], p[3 * i + 2] = (float)b[2 * BLOCK + i];
        return;
    }
    for (size_t i = 0; i < m; i++)
        p[3 * i] = (float)b[i], p[3 * i + 1] = (float)b[BLOCK + i], p[3 * i + 2] = (float)b[2 * BLOCK + i];
}

/* Ask for the block after next (the hardware's own prefetch alone leaves the loops waiting
 * for memory: 20% slower on 1M atoms); past the end of the atoms it does nothing. */
KINLINE void ahead(const float *p)
{
    for (int l = 0; l < 3 * BLOCK * (int)sizeof *p / 64; l++)
        __builtin_prefetch(p + 3 * 2 * BLOCK + 64 / sizeof *p * l, 1);
}

/* The bits of a shift: zero exactly when it is +0 (what kfloor gives for no move); OR-ing
 * them is a reduction the vectoriser takes, where a count of compares is not. */
KINLINE uint64_t bits(double n)
{
    uint64_t u;
    memcpy(&u, &n, sizeof u);
    return u;
}

/* The lower-triangular cell as scalars the loops keep in registers. */
typedef struct kcell {
    double i00, i10, i20, i11, i21, i22;   /* inverse */
    double v00, v10, v20, v11, v21, v22;   /* lattice vectors */
} kcell;

static kcell kcell_of(const ms_pbc_cell *c)
{
    kcell k = {c->inv[0][0], c->inv[1][0], c->inv[2][0], c->inv[1][1], c->inv[2][1],
               c->inv[2][2], c->v[0][0], c->v[1][0], c->v[2][0], c->v[1][1], c->v[2][1],
               c->v[2][2]};
    return k;
}

/* Move the atoms of b by -(n0 A + n1 B + n2 C), n = floor(fractional (b - o) + h) for
 * each atom (h = 0: into the cell at o; h = 1/2 with o the reference point per atom, the
 * image nearest it). Returns whether any atom moved. ref: per-atom origins, or NULL for o. */
KINLINE int shift_block(double *restrict b, const double *restrict ref, const double o[3],
                              double h, const kcell *restrict k)
{
    uint64_t moved = 0;
    for (size_t i = 0; i < BLOCK; i++) {
        double q0 = b[i] - (ref ? ref[i] : o[0]);
        double q1 = b[BLOCK + i] - (ref ? ref[BLOCK + i] : o[1]);
        double q2 = b[2 * BLOCK + i] - (ref ? ref[2 * BLOCK + i] : o[2]);
        double n0 = kfloor(q0 * k->i00 + q1 * k->i10 + q2 * k->i20 + h);
        double n1 = kfloor(q1 * k->i11 + q2 * k->i21 + h), n2 = kfloor(q2 * k->i22 + h);
        b[i] -= n0 * k->v00 + n1 * k->v10 + n2 * k->v20;
        b[BLOCK + i] -= n1 * k->v11 + n2 * k->v21;
        b[2 * BLOCK + i] -= n2 * k->v22;
        moved |= bits(n0) | bits(n1) | bits(n2);
    }
    return moved != 0;
}


/* The brick Ax x By x Cz: z first (moving by C), then y (by B), then x (by A). */
KINLINE int brick_block(double *restrict b, const double o[3], const kcell *restrict k)
{
    uint64_t moved = 0;
    for (size_t i = 0; i < BLOCK; i++) {
        double r0 = b[i] - o[0], r1 = b[BLOCK + i] - o[1], r2 = b[2 * BLOCK + i] - o[2];
        double q0 = r0, q1 = r1, q2 = r2;
        double n2 = kfloor(r2 / k->v22);
        r0 -= n2 * k->v20, r1 -= n2 * k->v21, r2 -= n2 * k->v22;
        double n1 = kfloor(r1 / k->v11);
        r0 -= n1 * k->v10, r1 -= n1 * k->v11;
        double n0 = kfloor(r0 / k->v00);
        r0 -= n0 * k->v00;
        b[i] += r0 - q0, b[BLOCK + i] += r1 - q1, b[2 * BLOCK + i] += r2 - q2;
        moved |= bits(n0) | bits(n1) | bits(n2);
    }
    return moved != 0;
}

/* The wrap kernels' loop: each block of p moved into the cell at origin (by brick_block
 * when brick, else by shift_block) and stored back when an atom moved. Inlined into each
 * caller, where brick is a constant. */
KINLINE void wrap_blocks(float *p, size_t n, const ms_pbc_cell *c, const double origin[3],
                         int brick)
{
    kcell k = kcell_of(c);
    block b;
    for (size_t s = 0; s < n; s += BLOCK) {
        size_t m = n - s < BLOCK ? n - s : BLOCK;
        ahead(p + 3 * s);
        load(p + 3 * s, m, b);
        if (brick ? brick_block(b, origin, &k) : shift_block(b, NULL, origin, 0, &k))
            store(p + 3 * s, m, b);
    }
}

MS_PBC_CLONES
void ms_pbc_wrap_run(float *p, size_t n, const ms_pbc_cell *c, const double origin[3])
{
    wrap_blocks(p, n, c, origin, 0);
}

MS_PBC_CLONES
void ms_pbc_wrap_run_brick(float *p, size_t n, const ms_pbc_cell *c, const double origin[3])
{
    wrap_blocks(p, n, c, origin, 1);
}

MS_PBC_CLONES
void ms_pbc_unwrap_run(float *p, const float *prev, size_t n, const ms_pbc_cell *c)
{
    kcell k = kcell_of(c);
    block b, r;
    const double zero[3] = {0, 0, 0};
    for (size_t s = 0; s < n; s += BLOCK) {
        size_t m = n - s < BLOCK ? n - s : BLOCK;
        ahead(p + 3 * s);
        load(p + 3 * s, m, b);
        load(prev + 3 * s, m, r);
        if (shift_block(b, r, zero, 0.5, &k)) store(p + 3 * s, m, b);
    }
}
