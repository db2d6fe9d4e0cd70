/* simd_avx2.c: the loops that run with AVX2 and FMA, eight voxels of a row at a time: the
 * density scatter (each atom's rows through one window of whole vectors along x, whose
 * distances and factors are computed once per atom and block), the density gather (eight
 * voxels summing the atoms of the cells around them in registers), and marching cubes'
 * inside bits (compare and movemask). The arithmetic is that of the plain loops lane by
 * lane, so the results are bit for bit the same. Built for every x86-64 compiler and
 * called only when the CPU has AVX2 and FMA; elsewhere these fall back to the plain loops. */
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

/* Add g * c (or g) to the 8 floats at p (lanes where g is 0 keep their value exactly);
 * through a masked load and store when only n < 8 of them are in the row. */
static inline void add_run(float *p, int n, __m256i mask, __m256 g, const __m256 *c)
{
    __m256 v = n == 8 ? _mm256_loadu_ps(p) : _mm256_maskload_ps(p, mask);
    v = c ? _mm256_fmadd_ps(g, *c, v) : _mm256_add_ps(v, g);
    if (n == 8) _mm256_storeu_ps(p, v);
    else _mm256_maskstore_ps(p, mask, v);
}

/* An atom's window along x: nvec whole vectors from xs covering every voxel its cutoff
 * can reach (ceil(x - r) .. floor(x + r); at 1 A one vector), moved left to end at the
 * row's end when it would run past it; `tail` lanes of the last vector lie in the row (8
 * unless the grid is narrower than the window). Its lanes' x distances and factors are
 * computed once per atom and block; every row of the atom then uses the same vectors. */
typedef struct window {
    int xs, nvec, tail;
    __m256i tailmask;
    float ax;                /* the atom's x from xs */
} window;

static int window_of(const ms_qsurf_slab *s, float x, float r, window *wd)
{
    int lo = MS_MAX(0, (int)ceilf(x - r)), hi = MS_MIN(s->nx - 1, (int)floorf(x + r));
    if (lo > hi) return 0;
    wd->nvec = (hi - lo + 8) / 8;
    wd->xs = MS_MAX(0, MS_MIN(lo, s->nx - 8 * wd->nvec));
    wd->tail = MS_MIN(8, s->nx - (wd->xs + 8 * (wd->nvec - 1)));
    wd->tailmask = _mm256_cmpgt_epi32(_mm256_set1_epi32(wd->tail),
                                      _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    wd->ax = x - (float)wd->xs;
    return 1;
}

/* Whether vector k of the window misses a row at squared distance dyz (with margin). */
static inline int vector_misses(const window *wd, int k, float dyz, float r2)
{
    float t = MS_MAX(0.0f, MS_MAX((float)(8 * k) - wd->ax, wd->ax - (float)(8 * k + 7)));
    return fmaf(t, t, dyz) > r2 * 1.001f + 1e-3f;
}

/* Per-axis factors exp2(w (v - c)^2) of v = v0..v1, into f[v - v0] (rounded up to 8). */
static void factors_avx2(float *f, int v0, int v1, float c, __m256 w)
{
    __m256 vc = _mm256_set1_ps(c);
    for (int v = v0; v <= v1; v += 8)
        _mm256_storeu_ps(f + (v - v0), factor_avx2(w, _mm256_sub_ps(lanes_from(v), vc)));
}

/* What the rows of one atom share: its window, the window's x distances and factors, the
 * exponent factor and cutoff, the colour. */
typedef struct atom_rows {
    window wd;
    const float *dx, *ex;
    __m256 w, elim, c[3];
    int colored;
    float r2;
} atom_rows;

/* Add the atom to the row at offset `off` of the density and colour arrays: dyz = dy^2 +
 * dz^2, eyz the row's y and z factors. */
static inline void row_avx2(const atom_rows *ar, ms_qsurf_slab *s, size_t off, float dyz,
                            float eyz)
{
    __m256 vdyz = _mm256_set1_ps(dyz), veyz = _mm256_set1_ps(eyz);
    int nvec = ar->wd.nvec;
    off += (size_t)ar->wd.xs;
    for (int k = 0; k < nvec; k++) {
        if (nvec > 1 && vector_misses(&ar->wd, k, dyz, ar->r2)) continue;
        __m256 dx = _mm256_loadu_ps(ar->dx + 8 * k);
        __m256 in = inside_avx2(_mm256_fmadd_ps(dx, dx, vdyz), ar->w, ar->elim);
        __m256 g = _mm256_and_ps(_mm256_mul_ps(_mm256_loadu_ps(ar->ex + 8 * k), veyz), in);
        int n = k + 1 < nvec ? 8 : ar->wd.tail;
        size_t o = off + 8 * (size_t)k;
        add_run(s->dens + o, n, ar->wd.tailmask, g, NULL);
        for (int c = 0; ar->colored && c < 3; c++)
            add_run(s->rgb[c] + o, n, ar->wd.tailmask, g, &ar->c[c]);
    }
}

/* Atom a (grid units, exponent factor a[3]) added to the block's voxels within its
 * cutoff, row by row, skipping rows outside the cutoff sphere. */
static void atom_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b,
                      const float *a, const float *c)
{
    atom_rows ar;
    ar.r2 = ag->elim / a[3];
    float r = ms_qsurf_reach(ar.r2);
    int z0 = MS_MAX(b->z0, (int)floorf(a[2] - r)), z1 = MS_MIN(b->z1, (int)ceilf(a[2] + r));
    int y0 = MS_MAX(b->y0, (int)floorf(a[1] - r)), y1 = MS_MIN(b->y1, (int)ceilf(a[1] + r));
    if (z0 > z1 || y0 > y1 || !window_of(s, a[0], r, &ar.wd)) return;
    float *dx = b->scratch, *ex = dx + s->nx + 16, *ey = ex + s->nx + 16;
    float *ez = ey + s->ny + 16;
    ar.w = _mm256_set1_ps(a[3]), ar.elim = _mm256_set1_ps(ag->elim);
    ar.dx = dx, ar.ex = ex, ar.colored = c != NULL;
    for (int k = 0; k < ar.wd.nvec; k++) {
        __m256 d = _mm256_sub_ps(lanes_from(ar.wd.xs + 8 * k), _mm256_set1_ps(a[0]));
        _mm256_storeu_ps(dx + 8 * k, d);
        _mm256_storeu_ps(ex + 8 * k, factor_avx2(ar.w, d));
    }
    for (int k = 0; c && k < 3; k++) ar.c[k] = _mm256_set1_ps(c[k]);
    factors_avx2(ey, y0, y1, a[1], ar.w);
    factors_avx2(ez, z0, z1, a[2], ar.w);
    for (int z = z0; z <= z1; z++) {
        float dz = (float)z - a[2], dz2 = dz * dz;
        for (int y = y0; y <= y1; y++) {
            float dy = (float)y - a[1], dyz = fmaf(dy, dy, dz2);
            if (a[3] * dyz < ag->elim) continue;
            size_t off = ((size_t)(z - s->zb) * s->ny + y) * s->nx;
            row_avx2(&ar, s, off, dyz, ey[y - y0] * ez[z - z0]);
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
