/* density.c: the CPU density map: the plain C loops (scatter: each atom adds its Gaussian
 * to the voxels within its cutoff, skipping rows outside the cutoff sphere, from per-axis
 * factors computed once per atom; gather: each voxel sums the atoms of the cells around
 * it), and the driver that splits a slab into cache-sized blocks of planes and rows handed
 * to all cores. A block is written by one thread only, and every voxel sums its atoms in
 * cell order, so the result does not depend on the thread count, the slab boundaries or
 * the loop chosen (scatter is the default: on 1M atoms at 1 A it took 0.6x the gather's
 * time). */
#include "config.h"
#include "surf/qsurf_impl.h"
#include "base/threads.h"

#include <stdlib.h>
#include <string.h>

float ms_qsurf_exp2(float e)
{
    return ms_qsurf_exp2_1(e);
}

/* Add atom (a, w, c) to the voxels x0..x1 of one row: dyz = dy^2 + dz^2, ex the x factors
 * from x0, eyz the row's y and z factors. */
static void row_plain(float *d, float *const rgb[3], size_t off, int x0, int x1, const float *a,
                      float dyz, float elim, const float *c, const float *ex, float eyz)
{
    for (int x = x0; x <= x1; x++) {
        float dx = (float)x - a[0];
        float e = a[3] * fmaf(dx, dx, dyz);
        if (e < elim) continue;
        float g = ex[x - x0] * eyz;
        d[off + x] += g;
        if (!c) continue;
        for (int k = 0; k < 3; k++) rgb[k][off + x] = fmaf(g, c[k], rgb[k][off + x]);
    }
}

/* Atom a (grid units, exponent factor a[3]) added to the block's voxels within its
 * cutoff, row by row, skipping rows outside the cutoff sphere. */
static void atom_plain(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b,
                      const float *a, const float *c)
{
    float r2 = ag->elim / a[3], r = ms_qsurf_reach(r2);
    int z0 = MS_MAX(b->z0, (int)floorf(a[2] - r)), z1 = MS_MIN(b->z1, (int)ceilf(a[2] + r));
    int y0 = MS_MAX(b->y0, (int)floorf(a[1] - r)), y1 = MS_MIN(b->y1, (int)ceilf(a[1] + r));
    int bx0 = MS_MAX(0, (int)floorf(a[0] - r)), bx1 = MS_MIN(s->nx - 1, (int)ceilf(a[0] + r));
    if (z0 > z1 || y0 > y1 || bx0 > bx1) return;
    float *ex = b->scratch, *ey = b->scratch + s->nx + 16;
    for (int x = bx0; x <= bx1; x++) ex[x - bx0] = ms_qsurf_factor(a[3], (float)x - a[0]);
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
            row_plain(s->dens, s->rgb, off, x0, x1, a, dyz, ag->elim, c, ex + (x0 - bx0),
                      ey[y - y0] * ez);
        }
    }
}

void ms_qsurf_scatter_plain(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    int lo[2], hi[2];
    ms_qsurf_block_cells(ag, b, lo, hi);
    for (int cz = lo[1]; cz <= hi[1]; cz++)
        for (int cy = lo[0]; cy <= hi[0]; cy++) {
            size_t row = ((size_t)cz * ag->nc[1] + cy) * ag->nc[0];
            for (size_t i = ag->cellstart[row]; i < ag->cellstart[row + ag->nc[0]]; i++)
                atom_plain(ag, s, b, ag->xyzw + 4 * i, ag->rgb ? ag->rgb + 4 * i : NULL);
        }
}

/* One voxel summed over atoms [b, e) of the table. */
static void voxel_plain(const ms_qsurf_atomgrid *ag, size_t b, size_t e, float x, float y,
                        float z, float acc[4])
{
    for (size_t i = b; i < e; i++) {
        const float *a = ag->xyzw + 4 * i;
        float dx = x - a[0], dy = y - a[1], dz = z - a[2];
        float e = a[3] * fmaf(dx, dx, fmaf(dy, dy, dz * dz));
        if (e < ag->elim) continue;
        float g = ms_qsurf_factor(a[3], dx) *
                  (ms_qsurf_factor(a[3], dy) * ms_qsurf_factor(a[3], dz));
        acc[0] += g;
        if (!ag->rgb) continue;
        for (int k = 0; k < 3; k++) acc[1 + k] = fmaf(g, ag->rgb[4 * i + k], acc[1 + k]);
    }
}

/* Cells [lo, hi] along axis d around coordinate v. */
static void cell_span(const ms_qsurf_atomgrid *ag, int d, float v0, float v1, int *lo, int *hi)
{
    *lo = ms_qsurf_cell_of(v0 - ag->cutmax, ag->cw[d], ag->nc[d]);
    *hi = ms_qsurf_cell_of(v1 + ag->cutmax, ag->cw[d], ag->nc[d]);
}

void ms_qsurf_gather_plain(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    for (int z = b->z0; z <= b->z1; z++)
        for (int y = b->y0; y <= b->y1; y++) {
            int cz0, cz1, cy0, cy1;
            cell_span(ag, 2, (float)z, (float)z, &cz0, &cz1);
            cell_span(ag, 1, (float)y, (float)y, &cy0, &cy1);
            size_t off = ((size_t)(z - s->zb) * s->ny + y) * s->nx;
            for (int x = 0; x < s->nx; x++) {
                float acc[4] = {0, 0, 0, 0};
                int cx0, cx1;
                cell_span(ag, 0, (float)x, (float)x, &cx0, &cx1);
                for (int cz = cz0; cz <= cz1; cz++)
                    for (int cy = cy0; cy <= cy1; cy++) {
                        size_t row = ((size_t)cz * ag->nc[1] + cy) * ag->nc[0];
                        voxel_plain(ag, ag->cellstart[row + cx0], ag->cellstart[row + cx1 + 1],
                                    (float)x, (float)y, (float)z, acc);
                    }
                s->dens[off + x] = acc[0];
                if (ag->rgb)
                    for (int k = 0; k < 3; k++) s->rgb[k][off + x] = acc[1 + k];
            }
        }
}

/* ---------------------------------------------------------------- the driver */

int ms_qsurf_have_simd(void)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return 0;
#endif
}

int ms_qsurf_cpu_kernel(void)
{
    const char *k = getenv("MOLSCOPE_QUICKSURF_KERNEL");
    int kind = k && strcmp(k, "gather") == 0 ? MS_QSURF_K_GATHER : MS_QSURF_K_SCATTER;
    int simd = !ms_env_flag("MOLSCOPE_NOSIMD") && ms_qsurf_have_simd();
    return kind | (simd ? MS_QSURF_K_SIMD : MS_QSURF_K_PLAIN);
}

const char *ms_qsurf_kernel_name(int kernel)
{
    static const char *names[4] = {"plain-scatter", "plain-gather", "avx2-scatter",
                                   "avx2-gather"};
    return names[kernel & 3];
}

typedef struct density_job {
    const ms_qsurf_atomgrid *ag;
    ms_qsurf_slab *s;
    int group, band, nbands, kernel;
} density_job;

static void zero_block(ms_qsurf_slab *s, const ms_qsurf_block *b)
{
    size_t n = (size_t)(b->y1 - b->y0 + 1) * s->nx;
    for (int z = b->z0; z <= b->z1; z++) {
        size_t off = ((size_t)(z - s->zb) * s->ny + b->y0) * s->nx;
        memset(s->dens + off, 0, n * sizeof(float));
        for (int k = 0; s->rgb[0] && k < 3; k++) memset(s->rgb[k] + off, 0, n * sizeof(float));
    }
}

static void density_blocks(void *ctx, size_t begin, size_t end, int thread)
{
    density_job *j = ctx;
    ms_qsurf_slab *s = j->s;
    for (size_t t = begin; t < end; t++) {
        ms_qsurf_block b;
        b.z0 = s->cz + (int)(t / (size_t)j->nbands) * j->group;
        b.z1 = MS_MIN(s->ze, b.z0 + j->group - 1);
        b.y0 = (int)(t % (size_t)j->nbands) * j->band;
        b.y1 = MS_MIN(s->ny - 1, b.y0 + j->band - 1);
        b.scratch = j->ag->scratch + (size_t)thread * j->ag->scratch_n;
        zero_block(s, &b);
        switch (j->kernel) {
        case MS_QSURF_K_SCATTER | MS_QSURF_K_SIMD: ms_qsurf_scatter_avx2(j->ag, s, &b); break;
        case MS_QSURF_K_GATHER | MS_QSURF_K_SIMD: ms_qsurf_gather_avx2(j->ag, s, &b); break;
        case MS_QSURF_K_GATHER: ms_qsurf_gather_plain(j->ag, s, &b); break;
        default: ms_qsurf_scatter_plain(j->ag, s, &b); break;
        }
    }
}

/* Blocks of up to MS_QSURF_BLOCK_PLANES planes and as many rows (8 at least) as keep the
 * block's voxels (density and colour) within about 256 KB, so that the atoms' writes hit
 * the cache. */
void ms_qsurf_density_cpu_with(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, int kernel)
{
    if ((kernel & MS_QSURF_K_SIMD) && !ms_qsurf_have_simd()) kernel &= ~MS_QSURF_K_SIMD;
    int planes = s->ze - s->cz + 1, groups;
    size_t voxel = s->rgb[0] ? 16 : 4;
    density_job j = {.ag = ag, .s = s, .kernel = kernel,
                     .group = MS_MIN(MS_QSURF_BLOCK_PLANES, planes)};
    groups = (planes + j.group - 1) / j.group;
    j.band = (int)MS_MAX(8, MS_MIN((size_t)s->ny, (1u << 18) / (voxel * s->nx * j.group)));
    j.nbands = (s->ny + j.band - 1) / j.band;
    ms_parallel_for((size_t)groups * j.nbands, 1, density_blocks, &j);
}

void ms_qsurf_density_cpu(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s)
{
    ms_qsurf_density_cpu_with(ag, s, ms_qsurf_cpu_kernel());
}
