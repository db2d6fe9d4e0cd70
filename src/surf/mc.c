/* mc.c: marching cubes over a volume streamed in slabs. Three passes over the rows of a
 * slab, each on all cores: count the crossing edges each grid point owns and the triangles
 * of each cell row; turn the counts into first indices (so the mesh grows to its exact
 * size, once per slab); then write the vertices (position interpolated on the edge,
 * normal from the density gradient by central differences, colour interpolated from the
 * colour texture) and the triangles, whose corners are looked up through the owning
 * point's first vertex. A vertex is made once and shared by every triangle around it. */
#include "config.h"
#include "surf/qsurf_impl.h"
#include "base/threads.h"

#include <stdlib.h>
#include <string.h>

size_t ms_qsurf_extract_bytes(int nx, int ny, int layers)
{
    size_t plane = (size_t)nx * (size_t)ny;
    return plane * (size_t)(layers + 1) * (sizeof(uint32_t) + 1) + plane * sizeof(float) +
           (size_t)ny * (size_t)(layers + 1) * 2 * sizeof(uint32_t);
}

/* gradm = inverse transpose of the matrix whose columns are the axes. */
static int gradient_matrix(ms_qsurf_extract *mc)
{
    double a[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = mc->axis[c][r];
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (!(fabs(det) > 1e-30) || !isfinite(det)) return -1;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            /* cofactor of a[r][c] over det is inverse[c][r], so gradm[r][c] = that. */
            mc->gradm[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
        }
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
    if (gradient_matrix(mc) < 0) {
        ms_error_set(err, "the volume's axes are degenerate");
        return -1;
    }
    size_t plane = (size_t)n[0] * (size_t)n[1], planes = (size_t)maxlayers + 1;
    mc->vbase = ms_alloc_array(plane * planes, sizeof(uint32_t));
    mc->flags = ms_alloc_array(plane * planes, 1);
    mc->shared = ms_alloc_array(plane, sizeof(float));
    mc->vrow = ms_alloc_array((size_t)n[1] * planes, sizeof(uint32_t));
    mc->trow = ms_alloc_array((size_t)n[1] * planes, sizeof(uint32_t));
    if (!mc->vbase || !mc->flags || !mc->shared || !mc->vrow || !mc->trow) {
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
    free(mc->flags);
    free(mc->shared);
    free(mc->vrow);
    free(mc->trow);
    mc->vbase = NULL, mc->flags = NULL, mc->shared = NULL, mc->vrow = mc->trow = NULL;
}

void ms_qsurf_extract_share(ms_qsurf_extract *mc, ms_qsurf_slab *s, int z0)
{
    if (z0 == 0 || z0 != mc->next_z0) return;
    size_t plane = (size_t)s->nx * s->ny;
    memcpy(s->dens + (size_t)(z0 - s->zb) * plane, mc->shared, plane * sizeof(float));
}

/* ---------------------------------------------------------------- one slab */

typedef struct ex_job {
    ms_qsurf_extract *mc;
    const ms_qsurf_slab *s;
    const ms_qsurf_mctab *tab;
    int z0, z1, nx, ny;
} ex_job;

static inline const float *drow(const ex_job *j, int y, int z)
{
    return j->s->dens + ((size_t)(z - j->s->zb) * j->ny + y) * j->nx;
}

static inline size_t point(const ex_job *j, int x, int y, int z)
{
    return ((size_t)(z - j->z0) * j->ny + y) * j->nx + x;
}

/* Flags of the edges owned by the points of row (y, z); returns their number. */
static uint32_t flag_row(const ex_job *j, int y, int z)
{
    const float *d = drow(j, y, z), *dy = y + 1 < j->ny ? drow(j, y + 1, z) : NULL;
    const float *dz = z > 0 ? drow(j, y, z - 1) : NULL;
    uint8_t *flags = j->mc->flags + point(j, 0, y, z);
    float iso = j->mc->iso;
    uint32_t n = 0;
    for (int x = 0; x < j->nx; x++) {
        int in = d[x] > iso, f = 0;
        if (x + 1 < j->nx && in != (d[x + 1] > iso)) f |= 1;
        if (dy && in != (dy[x] > iso)) f |= 2;
        if (dz && in != (dz[x] > iso)) f |= 4;
        flags[x] = (uint8_t)f;
        n += (uint32_t)__builtin_popcount((unsigned)f);
    }
    return n;
}

/* The inside bits of the four points (y, z), (y+1, z), (y, z+1), (y+1, z+1) at x, spread
 * to the cube index bits of the cell's low-x corners. */
static inline int column(const float *const r[4], int x, float iso)
{
    return (r[0][x] > iso) | (r[1][x] > iso) << 2 | (r[2][x] > iso) << 4 | (r[3][x] > iso) << 6;
}

static void cell_rows(const ex_job *j, int y, int z, const float *r[4])
{
    r[0] = drow(j, y, z), r[1] = drow(j, y + 1, z);
    r[2] = drow(j, y, z + 1), r[3] = drow(j, y + 1, z + 1);
}

static uint32_t tri_count_row(const ex_job *j, int y, int z)
{
    const float *r[4];
    cell_rows(j, y, z, r);
    uint32_t n = 0;
    int lo = column(r, 0, j->mc->iso);
    for (int x = 0; x + 1 < j->nx; x++) {
        int hi = column(r, x + 1, j->mc->iso);
        n += j->tab->ntri[lo | hi << 1];
        lo = hi;
    }
    return n;
}

static void count_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    for (size_t r = begin; r < end; r++) {
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        j->mc->vrow[r] = z > j->z0 || z == 0 ? flag_row(j, y, z) : 0;
        j->mc->trow[r] = z < j->z1 && y + 1 < j->ny ? tri_count_row(j, y, z) : 0;
    }
}

static inline float dval(const ex_job *j, const float *grid, int x, int y, int z)
{
    return grid[((size_t)(z - j->s->zb) * j->ny + y) * j->nx + x];
}

/* Density gradient at a grid point in index space (central differences, one-sided at the
 * volume's faces). */
static void gradient(const ex_job *j, int x, int y, int z, float g[3])
{
    const int *n = j->mc->n;
    int p[3] = {x, y, z};
    for (int d = 0; d < 3; d++) {
        int lo[3] = {x, y, z}, hi[3] = {x, y, z};
        lo[d] = MS_MAX(p[d] - 1, 0), hi[d] = MS_MIN(p[d] + 1, n[d] - 1);
        float a = dval(j, j->s->dens, lo[0], lo[1], lo[2]);
        float b = dval(j, j->s->dens, hi[0], hi[1], hi[2]);
        g[d] = hi[d] > lo[d] ? (b - a) / (float)(hi[d] - lo[d]) : 0.0f;
    }
}

static void vertex_color(const ex_job *j, size_t v, const int p[3], const int q[3], float t)
{
    ms_qsurf_color_t *out = j->mc->mesh->color + 4 * v;
    float c[3], m = 1.0f;
    for (int k = 0; k < 3; k++) {
        if (!j->mc->colored) {
            c[k] = j->mc->solid[k];
            continue;
        }
        float a = dval(j, j->s->rgb[k], p[0], p[1], p[2]);
        float b = dval(j, j->s->rgb[k], q[0], q[1], q[2]);
        c[k] = a + t * (b - a);
        m = MS_MAX(m, c[k]);
    }
    for (int k = 0; k < 3; k++) out[k] = ms_qsurf_pack_color(c[k] / m);
    out[3] = ms_qsurf_pack_color(1.0f);
}

/* Vertex v on the edge from point p along `axis` (x +1, y +1, z -1). */
static void emit(const ex_job *j, size_t v, int x, int y, int z, int axis)
{
    const ms_qsurf_extract *mc = j->mc;
    int p[3] = {x, y, z}, q[3] = {x, y, z};
    q[axis] += axis == 2 ? -1 : 1;
    float d0 = dval(j, j->s->dens, x, y, z), d1 = dval(j, j->s->dens, q[0], q[1], q[2]);
    float t = (mc->iso - d0) / (d1 - d0), g0[3], g1[3];
    gradient(j, x, y, z, g0);
    gradient(j, q[0], q[1], q[2], g1);
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
    len = len > 0.0 ? 1.0 / sqrt(len) : 0.0;
    for (int r = 0; r < 3; r++)
        mc->mesh->normal[3 * v + r] = ms_qsurf_pack_normal(len > 0.0 ? (float)(nrm[r] * len)
                                                                      : r == 2 ? 1.0f : 0.0f);
    vertex_color(j, v, p, q, t);
}

static void vertex_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    for (size_t r = begin; r < end; r++) {
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        if (!(z > j->z0 || z == 0)) continue;
        uint32_t v = j->mc->vrow[r];
        size_t p0 = point(j, 0, y, z);
        for (int x = 0; x < j->nx; x++) {
            int f = j->mc->flags[p0 + x];
            if (!f) continue;
            j->mc->vbase[p0 + x] = v;
            for (int axis = 0; axis < 3; axis++)
                if (f >> axis & 1) emit(j, v++, x, y, z, axis);
        }
    }
}

/* The vertex on edge e of cell (x, y, z): its owner point's first vertex plus the owner's
 * crossing edges before it (x, then y, then z). */
static inline uint32_t edge_vertex(const ex_job *j, int x, int y, int z, int e)
{
    int from = ms_qsurf_mc_edge_from[e], axis = e >> 2;
    int px = x + (from & 1), py = y + (from >> 1 & 1), pz = z + (from >> 2 & 1) + (axis == 2);
    size_t p = point(j, px, py, pz);
    unsigned below = (unsigned)j->mc->flags[p] & ((1u << axis) - 1u);
    return j->mc->vbase[p] + (uint32_t)__builtin_popcount(below);
}

static void triangle_rows(void *ctx, size_t begin, size_t end, int thread)
{
    ex_job *j = ctx;
    const ms_qsurf_mctab *tab = j->tab;
    for (size_t r = begin; r < end; r++) {
        int z = j->z0 + (int)(r / (size_t)j->ny), y = (int)(r % (size_t)j->ny);
        if (z >= j->z1 || y + 1 >= j->ny) continue;
        uint32_t *out = j->mc->mesh->index + 3 * (size_t)j->mc->trow[r];
        const float *rows[4];
        cell_rows(j, y, z, rows);
        int lo = column(rows, 0, j->mc->iso);
        for (int x = 0; x + 1 < j->nx; x++) {
            int hi = column(rows, x + 1, j->mc->iso), cube = lo | hi << 1;
            lo = hi;
            for (int k = 0; k < 3 * tab->ntri[cube]; k++)
                *out++ = edge_vertex(j, x, y, z, tab->tri[cube][k]);
        }
    }
}

/* Counts to first indices; the mesh grows to hold them. */
static int make_room(ex_job *j, size_t rows, ms_error *err)
{
    ms_qsurf_extract *mc = j->mc;
    size_t nv = mc->mesh->nv, nt = mc->mesh->nt;
    for (size_t r = 0; r < rows; r++) {
        uint32_t cv = mc->vrow[r], ct = mc->trow[r];
        if (nv + cv > UINT32_MAX || nt + ct > UINT32_MAX) {
            ms_error_set(err, "the surface has more than %u vertices or triangles", UINT32_MAX);
            return -1;
        }
        mc->vrow[r] = (uint32_t)nv, mc->trow[r] = (uint32_t)nt;
        nv += cv, nt += ct;
    }
    if (ms_qsurf_mesh_resize(mc->mesh, nv, nt) < 0) {
        ms_error_set(err, "out of memory for a mesh of %zu vertices and %zu triangles", nv, nt);
        return -1;
    }
    return 0;
}

/* Keep plane z1 (its first vertices, flags and density) for the next slab. */
static void keep_top_plane(ex_job *j)
{
    ms_qsurf_extract *mc = j->mc;
    size_t plane = (size_t)j->nx * j->ny, top = (size_t)(j->z1 - j->z0) * plane;
    memmove(mc->vbase, mc->vbase + top, plane * sizeof(uint32_t));
    memmove(mc->flags, mc->flags + top, plane);
    memcpy(mc->shared, drow(j, 0, j->z1), plane * sizeof(float));
    mc->next_z0 = j->z1;
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
                .nx = mc->n[0], .ny = mc->n[1]};
    size_t rows = (size_t)(z1 - z0 + 1) * (size_t)j.ny;
    ms_parallel_for(rows, 8, count_rows, &j);
    if (make_room(&j, rows, err) < 0) return -1;
    ms_parallel_for(rows, 8, vertex_rows, &j);
    ms_parallel_for(rows, 8, triangle_rows, &j);
    keep_top_plane(&j);
    return 0;
}
