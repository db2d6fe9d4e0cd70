/* simd_avx2.c: the loops that run with AVX2 and FMA, eight voxels of a row at a time: the
 * density scatter (an atom's run of a row in full vectors and one masked tail), the
 * density gather (eight voxels summing the atoms of the cells around them in registers),
 * and marching cubes' inside bits (compare and movemask). The arithmetic is that of the
 * plain loops lane by lane, so the results are bit for bit the same. Built for every
 * x86-64 compiler and called only when the CPU has AVX2 and FMA; elsewhere these fall back
 * to the plain loops. */
#include "config.h"
#include "surf/qsurf_impl.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

#pragma GCC push_options
#pragma GCC target("avx2,fma")

static inline __m256 exp2_avx2(__m256 e)
{
    __m256 fl = _mm256_floor_ps(e), f = _mm256_sub_ps(e, fl);
    __m256 p = _mm256_fmadd_ps(_mm256_set1_ps(MS_QSURF_EXP2_C4), f,
                               _mm256_set1_ps(MS_QSURF_EXP2_C3));
    p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(MS_QSURF_EXP2_C2));
    p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(MS_QSURF_EXP2_C1));
    p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(MS_QSURF_EXP2_C0));
    __m256i sh = _mm256_slli_epi32(_mm256_cvtps_epi32(fl), 23);
    return _mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(p), sh));
}

/* Per-axis factors exp2(w d^2) of eight distances (ms_qsurf_factor lane by lane). */
static inline __m256 factor_avx2(__m256 w, __m256 d)
{
    __m256 e = _mm256_mul_ps(w, _mm256_mul_ps(d, d));
    return exp2_avx2(_mm256_max_ps(e, _mm256_set1_ps(-126.0f)));
}

/* The lanes within the cutoff: w d2 >= elim. */
static inline __m256 inside_avx2(__m256 d2, __m256 w, __m256 elim)
{
    return _mm256_cmp_ps(_mm256_mul_ps(w, d2), elim, _CMP_GE_OQ);
}

static inline __m256 lanes_from(int x)
{
    return _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(x),
                                               _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
}

/* Add g * c to the 8 floats at p (lanes where g is 0 keep their value exactly); through a
 * masked load and store when only n < 8 of them may be touched. */
static inline void add_run(float *p, int n, __m256i mask, __m256 g, const float *c, int k)
{
    __m256 v = n == 8 ? _mm256_loadu_ps(p) : _mm256_maskload_ps(p, mask);
    v = c ? _mm256_fmadd_ps(g, _mm256_set1_ps(c[k]), v) : _mm256_add_ps(v, g);
    if (n == 8) _mm256_storeu_ps(p, v);
    else _mm256_maskstore_ps(p, mask, v);
}

/* Add atom (a, c) to the voxels x0..x1 of one row: dyz = dy^2 + dz^2, ex the x factors
 * (ex[i] for voxel ex0 + i, readable 8 past x1), eyz the row's y and z factors. Vectors are
 * whole 8-voxel runs of the row (the row belongs to this thread), the last one shifted left
 * to end at the row's end, so that stores are plain and forward to the next atom's loads;
 * voxels outside x0..x1 or the cutoff get 0. */
static void row_avx2(ms_qsurf_slab *s, size_t off, int x0, int x1, const float *a, float dyz,
                     float elim, const float *c, const float *ex, int ex0, float eyz)
{
    __m256 ax = _mm256_set1_ps(a[0]), w = _mm256_set1_ps(a[3]), vdyz = _mm256_set1_ps(dyz);
    __m256 vel = _mm256_set1_ps(elim), veyz = _mm256_set1_ps(eyz);
    __m256i lo = _mm256_set1_epi32(x0 - 1), hi = _mm256_set1_epi32(x1 + 1);
    int full = s->nx >= 8;
    for (int x = x0; x <= x1; x += 8) {
        int base = full ? MS_MIN(x, s->nx - 8) : x, n = full ? 8 : MS_MIN(8, x1 - x + 1);
        __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(base),
                                       _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        __m256i mine = _mm256_and_si256(_mm256_cmpgt_epi32(idx, lo), _mm256_cmpgt_epi32(hi, idx));
        mine = _mm256_and_si256(mine, _mm256_cmpgt_epi32(idx, _mm256_set1_epi32(x - 1)));
        __m256 dx = _mm256_sub_ps(_mm256_cvtepi32_ps(idx), ax);
        __m256 in = _mm256_and_ps(inside_avx2(_mm256_fmadd_ps(dx, dx, vdyz), w, vel),
                                  _mm256_castsi256_ps(mine));
        __m256 g = _mm256_and_ps(_mm256_mul_ps(_mm256_loadu_ps(ex + (base - ex0)), veyz), in);
        __m256i mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(n),
                                          _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        add_run(s->dens + off + base, n, mask, g, NULL, 0);
        for (int k = 0; c && k < 3; k++) add_run(s->rgb[k] + off + base, n, mask, g, c, k);
    }
}

/* Atom a (grid units, exponent factor a[3]) added to the block's voxels within its
 * cutoff, row by row, skipping rows outside the cutoff sphere. */
static void atom_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b,
                      const float *a, const float *c)
{
    float r2 = ag->elim / a[3], r = ms_qsurf_reach(r2);
    int z0 = MS_MAX(b->z0, (int)floorf(a[2] - r)), z1 = MS_MIN(b->z1, (int)ceilf(a[2] + r));
    int y0 = MS_MAX(b->y0, (int)floorf(a[1] - r)), y1 = MS_MIN(b->y1, (int)ceilf(a[1] + r));
    int bx0 = MS_MAX(0, (int)floorf(a[0] - r)), bx1 = MS_MIN(s->nx - 1, (int)ceilf(a[0] + r));
    if (z0 > z1 || y0 > y1 || bx0 > bx1) return;
    /* x factors for the whole vectors row_avx2 may use: from bx0 - 7 (or 0) on. */
    int ex0 = MS_MAX(0, bx0 - 7);
    float *ex = b->scratch, *ey = b->scratch + s->nx + 16;
    __m256 w = _mm256_set1_ps(a[3]), ax = _mm256_set1_ps(a[0]);
    for (int x = ex0; x <= bx1; x += 8)
        _mm256_storeu_ps(ex + (x - ex0), factor_avx2(w, _mm256_sub_ps(lanes_from(x), ax)));
    for (int y = y0; y <= y1; y++) ey[y - y0] = ms_qsurf_factor(a[3], (float)y - a[1]);
    for (int z = z0; z <= z1; z++) {
        float dz = (float)z - a[2], ez = ms_qsurf_factor(a[3], dz);
        for (int y = y0; y <= y1; y++) {
            float dy = (float)y - a[1], dyz = fmaf(dy, dy, dz * dz);
            if (a[3] * dyz < ag->elim) continue;
            float half = ms_qsurf_reach(MS_MAX(r2 - dyz, 0.0f));
            int x0 = MS_MAX(bx0, (int)floorf(a[0] - half));
            int x1 = MS_MIN(bx1, (int)ceilf(a[0] + half));
            size_t off = ((size_t)(z - s->zb) * s->ny + y) * s->nx;
            row_avx2(s, off, x0, x1, a, dyz, ag->elim, c, ex, ex0, ey[y - y0] * ez);
        }
    }
}

void ms_qsurf_scatter_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    int lo[2], hi[2];
    ms_qsurf_block_cells(ag, b, lo, hi);
    for (int cz = lo[1]; cz <= hi[1]; cz++)
        for (int cy = lo[0]; cy <= hi[0]; cy++) {
            size_t row = ((size_t)cz * ag->nc[1] + cy) * ag->nc[0];
            for (size_t i = ag->cellstart[row]; i < ag->cellstart[row + ag->nc[0]]; i++)
                atom_avx2(ag, s, b, ag->xyzw + 4 * i, ag->rgb ? ag->rgb + 4 * i : NULL);
        }
}

/* Eight voxels x..x+7 of row (y, z) summed over atoms [b, e). */
static void block_avx2(const ms_qsurf_atomgrid *ag, size_t b, size_t e, int x, float y, float z,
                       __m256 acc[4])
{
    __m256 xs = lanes_from(x), vel = _mm256_set1_ps(ag->elim);
    for (size_t i = b; i < e; i++) {
        const float *a = ag->xyzw + 4 * i;
        float dy = y - a[1], dz = z - a[2], dyz = fmaf(dy, dy, dz * dz);
        __m256 dx = _mm256_sub_ps(xs, _mm256_set1_ps(a[0])), w = _mm256_set1_ps(a[3]);
        __m256 in = inside_avx2(_mm256_fmadd_ps(dx, dx, _mm256_set1_ps(dyz)), w, vel);
        float eyz = ms_qsurf_factor(a[3], dy) * ms_qsurf_factor(a[3], dz);
        __m256 g = _mm256_and_ps(_mm256_mul_ps(factor_avx2(w, dx), _mm256_set1_ps(eyz)), in);
        acc[0] = _mm256_add_ps(acc[0], g);
        if (!ag->rgb) continue;
        for (int k = 0; k < 3; k++)
            acc[1 + k] = _mm256_fmadd_ps(g, _mm256_set1_ps(ag->rgb[4 * i + k]), acc[1 + k]);
    }
}

static void store_block(ms_qsurf_slab *s, size_t off, int n, __m256 acc[4])
{
    float tmp[8];
    _mm256_storeu_ps(tmp, acc[0]);
    for (int l = 0; l < n; l++) s->dens[off + l] = tmp[l];
    for (int k = 0; s->rgb[0] && k < 3; k++) {
        _mm256_storeu_ps(tmp, acc[1 + k]);
        for (int l = 0; l < n; l++) s->rgb[k][off + l] = tmp[l];
    }
}

void ms_qsurf_gather_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    for (int z = b->z0; z <= b->z1; z++)
        for (int y = b->y0; y <= b->y1; y++) {
            int c0[3], c1[3];
            c0[2] = ms_qsurf_cell_of((float)z - ag->cutmax, ag->cw[2], ag->nc[2]);
            c1[2] = ms_qsurf_cell_of((float)z + ag->cutmax, ag->cw[2], ag->nc[2]);
            c0[1] = ms_qsurf_cell_of((float)y - ag->cutmax, ag->cw[1], ag->nc[1]);
            c1[1] = ms_qsurf_cell_of((float)y + ag->cutmax, ag->cw[1], ag->nc[1]);
            size_t off = ((size_t)(z - s->zb) * s->ny + y) * s->nx;
            for (int x = 0; x < s->nx; x += 8) {
                __m256 acc[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(),
                                 _mm256_setzero_ps()};
                c0[0] = ms_qsurf_cell_of((float)x - ag->cutmax, ag->cw[0], ag->nc[0]);
                c1[0] = ms_qsurf_cell_of((float)(x + 7) + ag->cutmax, ag->cw[0], ag->nc[0]);
                for (int cz = c0[2]; cz <= c1[2]; cz++)
                    for (int cy = c0[1]; cy <= c1[1]; cy++) {
                        size_t row = ((size_t)cz * ag->nc[1] + cy) * ag->nc[0];
                        block_avx2(ag, ag->cellstart[row + c0[0]], ag->cellstart[row + c1[0] + 1],
                                   x, (float)y, (float)z, acc);
                    }
                store_block(s, off + x, MS_MIN(8, s->nx - x), acc);
            }
        }
}

/* Bit b of out[w] = d[64 w + b] > iso, for n values. */
void ms_qsurf_inside_bits_avx2(const float *d, int n, float iso, uint64_t *out)
{
    __m256 viso = _mm256_set1_ps(iso);
    int x = 0;
    for (; x + 64 <= n; x += 64) {
        uint64_t m = 0;
        for (int k = 0; k < 8; k++) {
            __m256 v = _mm256_loadu_ps(d + x + 8 * k);
            m |= (uint64_t)(unsigned)_mm256_movemask_ps(_mm256_cmp_ps(v, viso, _CMP_GT_OQ))
                 << (8 * k);
        }
        out[x / 64] = m;
    }
    if (x < n) ms_qsurf_inside_bits_plain(d + x, n - x, iso, out + x / 64);
}

#pragma GCC pop_options

#else

void ms_qsurf_inside_bits_avx2(const float *d, int n, float iso, uint64_t *out)
{
    ms_qsurf_inside_bits_plain(d, n, iso, out);
}

void ms_qsurf_scatter_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    ms_qsurf_scatter_plain(ag, s, b);
}

void ms_qsurf_gather_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    ms_qsurf_gather_plain(ag, s, b);
}

#endif
