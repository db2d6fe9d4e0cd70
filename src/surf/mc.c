/* mc.c: marching cubes over a volume streamed in slabs. Each row of grid points becomes
 * bitsets, 64 points a word: which points are inside, and which of the edges each point
 * owns (+x, +y, -z) cross the isovalue; so counting, finding the cells the surface passes
 * through and ranking vertices work a word at a time. Passes over the rows, each on all
 * cores: classify; count vertices and triangles; turn counts into first indices (the mesh
 * grows to its exact size, once per slab); write the vertices (position interpolated on
 * the edge, normal from the density gradient by central differences, colour interpolated
 * in the colour texture), recording each point's first vertex; write the triangles, their
 * corners found through the owning point. A vertex is made once and shared by every
 * triangle around it. */
#include "config.h"
#include "surf/qsurf_impl.h"
#include "base/threads.h"
#include "vecmath/vecmath.h"

#include <stdlib.h>
#include <string.h>

enum { B_IN = 0, B_X = 1, B_Y = 2, B_Z = 3 };   /* the bitsets of a row */

static inline int popcount64(uint64_t w)
{
    w = w - ((w >> 1) & 0x5555555555555555u);
    w = (w & 0x3333333333333333u) + ((w >> 2) & 0x3333333333333333u);
    w = (w + (w >> 4)) & 0x0f0f0f0f0f0f0f0fu;
    return (int)((w * 0x0101010101010101u) >> 56);
}

size_t ms_qsurf_extract_bytes(int nx, int ny, int layers)
{
    size_t plane = (size_t)nx * (size_t)ny, planes = (size_t)layers + 1;
    size_t rows = (size_t)ny * planes, words = ((size_t)nx + 63) / 64;
    return plane * planes * sizeof(uint32_t) + rows * words * 4 * sizeof(uint64_t) +
           (rows + 1) * 2 * sizeof(uint32_t);
}

/* gradm = inverse transpose of the matrix whose columns are the axes. */
static int gradient_matrix(ms_qsurf_extract *mc)
{
    double a[3][3], inv[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = mc->axis[c][r];
    if (ms_m3d_inverse(a, inv)) return -1;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) mc->gradm[r][c] = inv[c][r];
    return 0;
}

int ms_qsurf_extract_begin(ms_qsurf_extract *mc, const int n[3], const float origin[3],
                           const float axis[3][3], float iso, int colored, const float solid[3],
                           int maxlayers, ms_qsurf_mesh *mesh, ms_error *err)
{
    memset(mc, 0, sizeof *mc);
    for (int d = 0; d < 3; d++) {
        mc->n[d] = n[d];
        mc->origin[d] = origin[d];
        mc->solid[d] = solid ? solid[d] : 1.0f;
        for (int k = 0; k < 3; k++) mc->axis[d][k] = axis[d][k];
    }
    mc->iso = iso, mc->colored = colored, mc->maxlayers = maxlayers, mc->mesh = mesh;
    mc->words = (n[0] + 63) / 64;
    mc->aligned = 1;
    for (int d = 0; d < 3; d++)
        for (int k = 0; k < 3; k++) mc->aligned &= d == k || axis[d][k] == 0.0f;
    if (gradient_matrix(mc) < 0) {
        ms_error_set(err, "the volume's axes are degenerate");
        return -1;
    }
    size_t plane = (size_t)n[0] * (size_t)n[1], planes = (size_t)maxlayers + 1;
    size_t rows = (size_t)n[1] * planes;
    mc->vbase = ms_alloc_array(plane * planes, sizeof(uint32_t));
    ms_advise_huge(mc->vbase, plane * planes * sizeof(uint32_t));
    mc->bits = ms_calloc_array(rows * (size_t)mc->words * 4, sizeof(uint64_t));
    mc->vrow = ms_alloc_array(rows + 1, sizeof(uint32_t));
    mc->trow = ms_alloc_array(rows + 1, sizeof(uint32_t));
    if (!mc->vbase || !mc->bits || !mc->vrow || !mc->trow) {
        ms_qsurf_extract_end(mc);
        ms_error_set(err, "out of memory for marching cubes (%zu planes of %zu points)",
                     planes, plane);
        return -1;
    }
    (void)ms_qsurf_mc_table();
    return 0;
}

void ms_qsurf_extract_end(ms_qsurf_extract *mc)
{
    free(mc->vbase);
    free(mc->bits);
    free(mc->vrow);
    free(mc->trow);
    mc->vbase = NULL, mc->bits = NULL, mc->vrow = mc->trow = NULL;
}

/* ---------------------------------------------------------------- one slab */

typedef struct ex_job {
    ms_qsurf_extract *mc;
    const ms_qsurf_slab *s;
    const ms_qsurf_mctab *tab;
    int z0, z1, nx, ny, words, simd;
} ex_job;

static inline const float *drow(const ex_job *j, int y, int z)
{
    return j->s->dens + ((size_t)(z - j->s->zb) * j->ny + y) * j->nx;
}

static inline size_t point(const ex_job *j, int x, int y, int z)
{
    return ((size_t)(z - j->z0) * j->ny + y) * j->nx + x;
}

static inline size_t row_of(const ex_job *j, int y, int z)
{
    return (size_t)(z - j->z0) * j->ny + y;
}

static inline uint64_t *bits(const ex_job *j, size_t row, int k)
{
    return j->mc->bits + (row * 4 + (size_t)k) * (size_t)j->words;
}

/* Points of word w that have a +x neighbour (x <= nx - 2). */
static inline uint64_t has_next_x(const ex_job *j, int w)
{
    int last = j->nx - 2 - 64 * w;   /* highest valid bit */
    return last >= 63 ? ~(uint64_t)0 : last < 0 ? 0 : ((uint64_t)2 << last) - 1;
}

/* Bits of word w shifted so that bit b tells about point x + 1. */
static inline uint64_t next_x(const ex_job *j, const uint64_t *row, int w)
{
    return row[w] >> 1 | (w + 1 < j->words ? row[w + 1] << 63 : 0);
}

void ms_qsurf_inside_bits_plain(const float *d, int n, float iso, uint64_t *out)
{
    for (int w = 0; 64 * w < n; w++) {
        int x0 = 64 * w, m = MS_MIN(64, n - x0);
        uint64_t bitsw = 0;
        for (int b = 0; b < m; b++) bitsw |= (uint64_t)(d[x0 + b] > iso) << b;
        out[w] = bitsw;
    }
}

static void classify_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    for (size_t r = begin; r < end; r++) {
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        if (j->simd) ms_qsurf_inside_bits_avx2(drow(j, y, z), j->nx, j->mc->iso, bits(j, r, B_IN));
        else ms_qsurf_inside_bits_plain(drow(j, y, z), j->nx, j->mc->iso, bits(j, r, B_IN));
    }
}

/* Crossing bits of the edges the points of row (y, z) own; returns their number. */
static uint32_t cross_row(const ex_job *j, int y, int z)
{
    size_t r = row_of(j, y, z);
    const uint64_t *in = bits(j, r, B_IN);
    const uint64_t *iny = y + 1 < j->ny ? bits(j, r + 1, B_IN) : NULL;
    const uint64_t *inz = z > j->z0 ? bits(j, r - (size_t)j->ny, B_IN) : NULL;
    uint64_t *xb = bits(j, r, B_X), *yb = bits(j, r, B_Y), *zb = bits(j, r, B_Z);
    uint32_t n = 0;
    for (int w = 0; w < j->words; w++) {
        xb[w] = (in[w] ^ next_x(j, in, w)) & has_next_x(j, w);
        yb[w] = iny ? in[w] ^ iny[w] : 0;
        zb[w] = inz ? in[w] ^ inz[w] : 0;
        n += (uint32_t)(popcount64(xb[w]) + popcount64(yb[w]) + popcount64(zb[w]));
    }
    return n;
}

/* The cells of row (y, z) in word w that the surface passes through, with the inside bits
 * of their eight corners (corner i = dx + 2 dy + 4 dz at bit b for the cell x = 64 w + b). */
static inline uint64_t cell_word(const ex_job *j, int y, int z, int w, uint64_t c[8])
{
    size_t r = row_of(j, y, z);
    size_t up = r + (size_t)j->ny;
    const uint64_t *rows[4] = {bits(j, r, B_IN), bits(j, r + 1, B_IN), bits(j, up, B_IN),
                               bits(j, up + 1, B_IN)};
    uint64_t any = 0, all = ~(uint64_t)0;
    for (int k = 0; k < 4; k++) {
        c[2 * k] = rows[k][w], c[2 * k + 1] = next_x(j, rows[k], w);
        any |= c[2 * k] | c[2 * k + 1], all &= c[2 * k] & c[2 * k + 1];
    }
    return any & ~all & has_next_x(j, w);
}

static inline int cube_at(const uint64_t c[8], int b)
{
    int cube = 0;
    for (int i = 0; i < 8; i++) cube |= (int)(c[i] >> b & 1) << i;
    return cube;
}

static uint32_t count_triangles(const ex_job *j, int y, int z)
{
    uint32_t n = 0;
    for (int w = 0; w < j->words; w++) {
        uint64_t c[8], act = cell_word(j, y, z, w, c);
        for (; act; act &= act - 1) n += j->tab->ntri[cube_at(c, __builtin_ctzll(act))];
    }
    return n;
}

static void count_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    for (size_t r = begin; r < end; r++) {
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        j->mc->vrow[r] = z > j->z0 || z == 0 ? cross_row(j, y, z) : 0;
        j->mc->trow[r] = z < j->z1 && y + 1 < j->ny ? count_triangles(j, y, z) : 0;
    }
}

/* Density gradient at a grid point in index space (central differences, one-sided at the
 * volume's faces). */
static void gradient(const ex_job *j, int x, int y, int z, float g[3])
{
    const float *p = j->s->dens + ((size_t)(z - j->s->zb) * j->ny + y) * j->nx + x;
    ptrdiff_t step[3] = {1, j->nx, (ptrdiff_t)j->nx * j->ny};
    int c[3] = {x, y, z};
    if (x > 0 && y > 0 && z > 0 && x + 1 < j->nx && y + 1 < j->ny && z + 1 < j->mc->n[2]) {
        /* Inside the volume: halving is exact, so this is the division below, bit for bit. */
        for (int d = 0; d < 3; d++) g[d] = (p[step[d]] - p[-step[d]]) * 0.5f;
        return;
    }
    for (int d = 0; d < 3; d++) {
        int lo = c[d] > 0, hi = c[d] + 1 < j->mc->n[d];
        g[d] = lo + hi ? (p[hi * step[d]] - p[-lo * step[d]]) / (float)(lo + hi) : 0.0f;
    }
}

/* The colour at t between points a and b (offsets into the colour grids). */
static void vertex_color(const ex_job *j, size_t v, size_t a, size_t b, float t)
{
    ms_qsurf_color_t *out = j->mc->mesh->color + 4 * v;
    float c[3], m = 1.0f;
    for (int k = 0; k < 3; k++) {
        if (!j->mc->colored) {
            c[k] = j->mc->solid[k];
            continue;
        }
        const float *grid = j->s->rgb[k];
        c[k] = grid[a] + t * (grid[b] - grid[a]);
        m = MS_MAX(m, c[k]);
    }
    for (int k = 0; k < 3; k++) out[k] = ms_qsurf_pack_color(m == 1.0f ? c[k] : c[k] / m);
    out[3] = ms_qsurf_pack_color(1.0f);
}

static void put_normal(const ex_job *j, size_t v, const double nrm[3], double len)
{
    len = len > 0.0 ? 1.0 / sqrt(len) : 0.0;
    for (int r = 0; r < 3; r++)
        j->mc->mesh->normal[3 * v + r] =
            ms_qsurf_pack_normal(len > 0.0 ? (float)(nrm[r] * len) : r == 2 ? 1.0f : 0.0f);
}

/* Position and normal of vertex v at t from p to q, on any axes. */
static void place_skewed(const ex_job *j, size_t v, const int p[3], const int q[3], float t,
                         const float g0[3], const float g1[3])
{
    const ms_qsurf_extract *mc = j->mc;
    double nrm[3] = {0, 0, 0}, len = 0.0;
    for (int r = 0; r < 3; r++) {
        double pos = mc->origin[r];
        for (int k = 0; k < 3; k++) {
            pos += (p[k] + (double)t * (q[k] - p[k])) * mc->axis[k][r];
            nrm[r] -= mc->gradm[r][k] * (g0[k] + t * (g1[k] - g0[k]));
        }
        mc->mesh->pos[3 * v + r] = (ms_qsurf_pos_t)pos;
        len += nrm[r] * nrm[r];
    }
    put_normal(j, v, nrm, len);
}

/* The same on axes along x, y and z: the terms of the other axes, exact zeros there, are
 * left out, which changes no bit. */
static void place_aligned(const ex_job *j, size_t v, const int p[3], int axis, int dq, float t,
                          const float g0[3], const float g1[3])
{
    const ms_qsurf_extract *mc = j->mc;
    double nrm[3], len = 0.0;
    for (int r = 0; r < 3; r++) {
        double c = r == axis ? p[r] + (double)t * dq : (double)p[r];
        mc->mesh->pos[3 * v + r] = (ms_qsurf_pos_t)(mc->origin[r] + c * mc->axis[r][r]);
        nrm[r] = 0.0 - mc->gradm[r][r] * (g0[r] + t * (g1[r] - g0[r]));
        len += nrm[r] * nrm[r];
    }
    put_normal(j, v, nrm, len);
}

/* Vertex v on the edge from point p along `axis` (x +1, y +1, z -1). */
static void emit(const ex_job *j, size_t v, int x, int y, int z, int axis)
{
    const ms_qsurf_extract *mc = j->mc;
    int p[3] = {x, y, z}, q[3] = {x, y, z}, dq = axis == 2 ? -1 : 1;
    ptrdiff_t step[3] = {1, j->nx, (ptrdiff_t)j->nx * j->ny};
    q[axis] += dq;
    size_t a = ((size_t)(z - j->s->zb) * j->ny + y) * j->nx + x;
    size_t b = (size_t)((ptrdiff_t)a + dq * step[axis]);
    float d0 = j->s->dens[a], d1 = j->s->dens[b];
    float t = (mc->iso - d0) / (d1 - d0), g0[3], g1[3];
    gradient(j, x, y, z, g0);
    gradient(j, q[0], q[1], q[2], g1);
    if (mc->aligned) place_aligned(j, v, p, axis, dq, t, g0, g1);
    else place_skewed(j, v, p, q, t, g0, g1);
    vertex_color(j, v, a, b, t);
}

/* Ask for the cache lines the vertices of word w of row (y, z) will read: the density of
 * the row and its four neighbours, the colour of the row and of the edges' far ends (y + 1,
 * z - 1). */
static void prefetch_word(const ex_job *j, int y, int z, int w)
{
    int zl = MS_MAX(z - 1, j->s->zb), zh = MS_MIN(z + 1, j->s->ze);
    int yl = MS_MAX(y - 1, 0), yh = MS_MIN(y + 1, j->ny - 1);
    const float *rows[14] = {drow(j, y, z), drow(j, yl, z), drow(j, yh, z), drow(j, y, zl),
                             drow(j, y, zh)};
    size_t at[3] = {((size_t)(z - j->s->zb) * j->ny + y) * j->nx,
                    ((size_t)(z - j->s->zb) * j->ny + yh) * j->nx,
                    ((size_t)(zl - j->s->zb) * j->ny + y) * j->nx};
    for (int k = 0; k < 3 && j->mc->colored; k++)
        for (int r = 0; r < 3; r++) rows[5 + 3 * k + r] = j->s->rgb[k] + at[r];
    int x0 = 64 * w, n = MS_MIN(64, j->nx - x0);
    for (int r = 0; r < 14; r++)
        for (int x = 0; rows[r] && x < n; x += 16) __builtin_prefetch(rows[r] + x0 + x);
}

/* Vertices in owner order: points by x, each point's edges x, y, z. */
static void vertex_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    for (size_t r = begin; r < end; r++) {
        uint32_t v = j->mc->vrow[r];
        if (v == j->mc->vrow[r + 1]) continue;
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        const uint64_t *xb = bits(j, r, B_X), *yb = bits(j, r, B_Y), *zb = bits(j, r, B_Z);
        for (int w = 0; w < j->words; w++) {
            if (w + 1 < j->words && (xb[w + 1] | yb[w + 1] | zb[w + 1]))
                prefetch_word(j, y, z, w + 1);
            for (uint64_t m = xb[w] | yb[w] | zb[w]; m; m &= m - 1) {
                int b = __builtin_ctzll(m), x = 64 * w + b;
                j->mc->vbase[point(j, x, y, z)] = v;
                if (xb[w] >> b & 1) emit(j, v++, x, y, z, 0);
                if (yb[w] >> b & 1) emit(j, v++, x, y, z, 1);
                if (zb[w] >> b & 1) emit(j, v++, x, y, z, 2);
            }
        }
    }
}

/* Where the vertices of a row of cells are found: for each of the four rows of owner
 * points around it (dy + 2 dz), their first vertices and their x and y crossing bits. */
typedef struct owner_rows {
    const uint32_t *vbase[4];
    const uint64_t *xbits[4], *ybits[4];
} owner_rows;

static void owner_rows_of(const ex_job *j, int y, int z, owner_rows *o)
{
    for (int k = 0; k < 4; k++) {
        int py = y + (k & 1), pz = z + (k >> 1);
        size_t r = row_of(j, py, pz);
        o->vbase[k] = j->mc->vbase + point(j, 0, py, pz);
        o->xbits[k] = bits(j, r, B_X), o->ybits[k] = bits(j, r, B_Y);
    }
}

/* The vertex of cell x's edge with owner code `own` (ms_qsurf_mctab): its owner point's
 * first vertex plus the owner's crossing edges before it (x, then y, then z). */
static inline uint32_t edge_vertex(const owner_rows *o, int x, int own)
{
    int k = own >> 1 & 3, axis = own >> 3, px = x + (own & 1), w = px >> 6, b = px & 63;
    uint32_t xr = (uint32_t)(o->xbits[k][w] >> b & 1), yr = (uint32_t)(o->ybits[k][w] >> b & 1);
    return o->vbase[k][px] + (axis > 0 ? xr : 0) + (axis > 1 ? yr : 0);
}

static void triangle_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    const ms_qsurf_mctab *tab = j->tab;
    for (size_t r = begin; r < end; r++) {
        if (j->mc->trow[r] == j->mc->trow[r + 1]) continue;
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        uint32_t *out = j->mc->mesh->index + 3 * (size_t)j->mc->trow[r], v[12];
        owner_rows o;
        owner_rows_of(j, y, z, &o);
        for (int w = 0; w < j->words; w++) {
            uint64_t c[8], act = cell_word(j, y, z, w, c);
            for (; act; act &= act - 1) {
                int b = __builtin_ctzll(act), cube = cube_at(c, b), x = 64 * w + b;
                for (int e = 0; e < tab->nedge[cube]; e++)
                    v[e] = edge_vertex(&o, x, tab->owner[tab->edges[cube][e]]);
                for (int k = 0; k < 3 * tab->ntri[cube]; k++) *out++ = v[tab->corner[cube][k]];
            }
        }
    }
}

/* Counts to first indices; the mesh grows to hold them. */
static int make_room(ex_job *j, size_t rows, ms_error *err)
{
    ms_qsurf_extract *mc = j->mc;
    size_t nv = mc->mesh->nv, nt = mc->mesh->nt;
    for (size_t r = 0; r <= rows; r++) {
        uint32_t cv = r < rows ? mc->vrow[r] : 0, ct = r < rows ? mc->trow[r] : 0;
        if (nv + cv > UINT32_MAX || nt + ct > UINT32_MAX) {
            ms_error_set(err, "the surface has more than %u vertices or triangles", UINT32_MAX);
            return -1;
        }
        mc->vrow[r] = (uint32_t)nv, mc->trow[r] = (uint32_t)nt;
        nv += cv, nt += ct;
    }
    if (ms_qsurf_mesh_fits(mc, nv, nt, err) < 0) return -1;
    if (ms_qsurf_mesh_resize(mc->mesh, nv, nt) < 0) {
        ms_error_set(err, "out of memory for a mesh of %zu vertices and %zu triangles", nv, nt);
        return -1;
    }
    return 0;
}

/* Keep plane z1 (its first vertices and crossing bits) for the next slab. */
static void keep_top_plane(ex_job *j)
{
    ms_qsurf_extract *mc = j->mc;
    size_t plane = (size_t)j->nx * j->ny, top = (size_t)(j->z1 - j->z0);
    size_t rowwords = 4 * (size_t)j->words * j->ny;
    memmove(mc->vbase, mc->vbase + top * plane, plane * sizeof(uint32_t));
    memmove(mc->bits, mc->bits + top * rowwords, rowwords * sizeof(uint64_t));
    mc->next_z0 = j->z1;
}

/* Plane z0's crossing bits, as the slab before would have left them; returns their
 * number. Row ny (free until the next slab's classification) holds plane z0 - 1's inside
 * bits meanwhile. */
static size_t rebuild_bits(ex_job *j)
{
    size_t n = 0;
    uint64_t *below = bits(j, (size_t)j->ny, B_IN);
    for (int y = 0; y < j->ny; y++)
        ms_qsurf_inside_bits_plain(drow(j, y, j->z0), j->nx, j->mc->iso, bits(j, (size_t)y, B_IN));
    for (int y = 0; y < j->ny; y++) {
        const uint64_t *in = bits(j, (size_t)y, B_IN);
        const uint64_t *iny = y + 1 < j->ny ? bits(j, (size_t)y + 1, B_IN) : NULL;
        uint64_t *xb = bits(j, (size_t)y, B_X), *yb = bits(j, (size_t)y, B_Y);
        uint64_t *zb = bits(j, (size_t)y, B_Z);
        ms_qsurf_inside_bits_plain(drow(j, y, j->z0 - 1), j->nx, j->mc->iso, below);
        for (int w = 0; w < j->words; w++) {
            xb[w] = (in[w] ^ next_x(j, in, w)) & has_next_x(j, w);
            yb[w] = iny ? in[w] ^ iny[w] : 0;
            zb[w] = in[w] ^ below[w];
            n += (size_t)(popcount64(xb[w]) + popcount64(yb[w]) + popcount64(zb[w]));
        }
    }
    return n;
}

int ms_qsurf_extract_resume(ms_qsurf_extract *mc, const ms_qsurf_slab *s, int z0,
                            ms_error *err)
{
    ex_job j = {.mc = mc, .s = s, .z0 = z0, .z1 = z0, .nx = mc->n[0], .ny = mc->n[1],
                .words = mc->words};
    if (z0 <= 0 || z0 >= mc->n[2] - 1 || mc->maxlayers < 1 || s->zb > z0 - 1 || s->ze < z0) {
        ms_error_set(err, "marching cubes: cannot resume at plane %d", z0);
        return -1;
    }
    size_t n = rebuild_bits(&j);
    if (n > mc->mesh->nv) {
        ms_error_set(err, "marching cubes: the mesh lacks plane %d's vertices", z0);
        return -1;
    }
    uint32_t v = (uint32_t)(mc->mesh->nv - n);
    for (int y = 0; y < j.ny; y++) {
        const uint64_t *xb = bits(&j, (size_t)y, B_X), *yb = bits(&j, (size_t)y, B_Y);
        const uint64_t *zb = bits(&j, (size_t)y, B_Z);
        for (int w = 0; w < j.words; w++)
            for (uint64_t m = xb[w] | yb[w] | zb[w]; m; m &= m - 1) {
                int b = __builtin_ctzll(m);
                mc->vbase[point(&j, 64 * w + b, y, z0)] = v;
                v += (uint32_t)((xb[w] >> b & 1) + (yb[w] >> b & 1) + (zb[w] >> b & 1));
            }
    }
    mc->next_z0 = z0;
    return 0;
}

int ms_qsurf_extract_slab(ms_qsurf_extract *mc, const ms_qsurf_slab *s, int z0, int z1,
                          ms_error *err)
{
    int nz = mc->n[2];
    if (z0 != mc->next_z0 || z1 <= z0 || z1 - z0 > mc->maxlayers || z1 > nz - 1 ||
        s->zb > MS_MAX(z0 - 1, 0) || s->ze < MS_MIN(z1 + 1, nz - 1) || s->nx != mc->n[0] ||
        s->ny != mc->n[1] || (mc->colored && !s->rgb[0])) {
        ms_error_set(err, "marching cubes: slab %d..%d out of order or not held", z0, z1);
        return -1;
    }
    ex_job j = {.mc = mc, .s = s, .tab = ms_qsurf_mc_table(), .z0 = z0, .z1 = z1,
                .nx = mc->n[0], .ny = mc->n[1], .words = mc->words,
                .simd = ms_qsurf_cpu_kernel() & MS_QSURF_K_SIMD};
    size_t rows = (size_t)(z1 - z0 + 1) * (size_t)j.ny;
    ms_parallel_for(rows, 16, classify_rows, &j);
    ms_parallel_for(rows, 16, count_rows, &j);
    if (make_room(&j, rows, err) < 0) return -1;
    ms_parallel_for(rows, 8, vertex_rows, &j);
    ms_parallel_for(rows, 8, triangle_rows, &j);
    keep_top_plane(&j);
    return 0;
}
