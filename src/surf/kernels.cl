/* kernels.cl: QuickSurf's OpenCL kernels (OpenCL C 1.2), built into molscope as a string
 * (the build turns this file into kernels.inc). A slab stays on the device from density to
 * mesh: qs_density sums the atoms into the slab's planes; marching cubes then counts each
 * work-item's vertices and triangles (qs_count), turns the counts into first indices by a
 * prefix sum (qs_scan, qs_scan_add), and writes the vertices (qs_vertices) and the indexed
 * triangles (qs_triangles). The order is the host extractor's (mc.c): vertices by owner
 * point, x fastest, each point's edges +x, +y, -z; triangles by cell; so the mesh is the
 * host's mesh, index for index. Work-groups cover blocks of 8x8x8 grid points; a work-item
 * takes four of them (four planes in the density, four points of a row in marching cubes).
 * The host passes QS_C0..QS_C4 (the exp2 polynomial) and QS_MAXTRI as build options. */
#pragma OPENCL FP_CONTRACT OFF

/* ---------------------------------------------------------------- density */

/* 2^e for e <= 0 with the CPU loops' polynomial and fused multiply-adds (qsurf_impl.h). */
static float qs_exp2(float e)
{
    float fl = floor(e), f = e - fl;
    float p = fma(fma(fma(fma(QS_C4, f, QS_C3), f, QS_C2), f, QS_C1), f, QS_C0);
    return as_float(as_int(p) + (int)fl * 8388608);
}

static float qs_factor(float w, float d)
{
    return qs_exp2(max(w * (d * d), -126.0f));
}

static int qs_cell(float v, float w, int n)
{
    int c = (int)(v / w);
    return c < 0 ? 0 : c >= n ? n - 1 : c;
}

/* Planes cz..ze of the slab whose first plane is zb: each work-item sums the atoms of the
 * cells around its 8x8x8 block into four voxels along z, in the atom table's order and
 * with the CPU's arithmetic, so the density is the CPU's bit for bit. */
__kernel __attribute__((reqd_work_group_size(8, 8, 2)))
void qs_density(__global const float4 *atoms, __global const float4 *colors,
                __global const uint *cellstart, int4 nc, float4 cw, float cut, float elim,
                int4 dims, int cz, int ze, int colored, __global float *dens,
                __global float *red, __global float *green, __global float *blue)
{
    int nx = dims.x, ny = dims.y, zb = dims.w;
    int x = get_global_id(0), y = get_global_id(1);
    int bx = get_group_id(0) * 8, by = get_group_id(1) * 8, bz = cz + get_group_id(2) * 8;
    int z = bz + get_local_id(2) * 4;
    int cx0 = qs_cell(bx - cut, cw.x, nc.x), cx1 = qs_cell(bx + 7 + cut, cw.x, nc.x);
    int cy0 = qs_cell(by - cut, cw.y, nc.y), cy1 = qs_cell(by + 7 + cut, cw.y, nc.y);
    int cz0 = qs_cell(bz - cut, cw.z, nc.z), cz1 = qs_cell(bz + 7 + cut, cw.z, nc.z);
    float d[4] = {0, 0, 0, 0}, r[4] = {0, 0, 0, 0};
    float g[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0};
    for (int k = cz0; k <= cz1; k++)
        for (int j = cy0; j <= cy1; j++) {
            int row = (k * nc.y + j) * nc.x;
            uint end = cellstart[row + cx1 + 1];
            for (uint i = cellstart[row + cx0]; i < end; i++) {
                float4 a = atoms[i];
                float dx = (float)x - a.x, dy = (float)y - a.y;
                float ex = qs_factor(a.w, dx), ey = qs_factor(a.w, dy);
                float4 c = colored ? colors[i] : (float4)(0.0f);
                for (int p = 0; p < 4; p++) {
                    float dz = (float)(z + p) - a.z;
                    float e = a.w * fma(dx, dx, fma(dy, dy, dz * dz));
                    if (e < elim) continue;
                    float v = ex * (ey * qs_factor(a.w, dz));
                    d[p] += v;
                    r[p] = fma(v, c.x, r[p]), g[p] = fma(v, c.y, g[p]);
                    b[p] = fma(v, c.z, b[p]);
                }
            }
        }
    if (x >= nx || y >= ny) return;
    for (int p = 0; p < 4 && z + p <= ze; p++) {
        size_t o = ((size_t)(z + p - zb) * ny + y) * nx + x;
        dens[o] = d[p];
        if (colored) red[o] = r[p], green[o] = g[p], blue[o] = b[p];
    }
}

/* ---------------------------------------------------------------- marching cubes
 * dims = (nx, ny, nz, zb): the grid and the first plane the slab holds; span = (z0, z1,
 * nix, 0): the slab's cell layers [z0, z1) and the work-items per row. Work-item (ix, y,
 * z - z0) takes points x0 = 4 ix .. x0 + 3 of row (y, z) and the cells at them; it reads
 * each row around them once, as bits: bit i of a row = point x0 + i is inside. */

typedef struct qs_grid {
    int nx, ny, nz, zb, z0, z1, nix;
    float iso;
} qs_grid;

static qs_grid qs_grid_of(int4 dims, int4 span, float iso)
{
    qs_grid g = {dims.x, dims.y, dims.z, dims.w, span.x, span.y, span.z, iso};
    return g;
}

static size_t qs_at(qs_grid g, int x, int y, int z)
{
    return ((size_t)(z - g.zb) * g.ny + y) * g.nx + x;
}

static size_t qs_item(qs_grid g, int ix, int y, int z)
{
    return ((size_t)(z - g.z0) * g.ny + y) * g.nix + ix;
}

/* Inside bits of points x0 .. x0 + n - 1 of row (y, z); 0 past the grid. */
static uint qs_row(qs_grid g, __global const float *dens, int x0, int y, int z, int n)
{
    uint bits = 0;
    if (y >= g.ny) return 0;
    __global const float *d = dens + qs_at(g, x0, y, z);
    for (int i = 0; i < n && x0 + i < g.nx; i++) bits |= (uint)(d[i] > g.iso) << i;
    return bits;
}

/* Bits of the points x0 .. x0 + n - 1 that have a +x neighbour. */
static uint qs_with_next(qs_grid g, int x0, int n)
{
    int k = min(n, g.nx - 1 - x0);
    return k <= 0 ? 0u : (1u << k) - 1;
}

/* The crossing edges the item's points own: +x, +y, -z (bit i for point x0 + i). */
typedef struct qs_edges {
    uint x, y, z;
} qs_edges;

static qs_edges qs_edges_of(qs_grid g, __global const float *dens, int x0, int y, int z)
{
    uint r = qs_row(g, dens, x0, y, z, 5), pts = (1u << min(4, g.nx - x0)) - 1;
    qs_edges e = {(r ^ r >> 1) & qs_with_next(g, x0, 4), 0, 0};
    if (y + 1 < g.ny) e.y = (r ^ qs_row(g, dens, x0, y + 1, z, 4)) & pts;
    if (z > 0) e.z = (r ^ qs_row(g, dens, x0, y, z - 1, 4)) & pts;
    return e;
}

/* The corner bits of cell x0 + i (corner dx + 2 dy + 4 dz, as mc.c) from the rows
 * r[dz][dy] around it. */
static uint qs_cube(const uint r[2][3], int i)
{
    uint c = 0;
    for (int k = 0; k < 4; k++) c |= (r[k >> 1][k & 1] >> i & 3) << (2 * k);
    return c;
}

/* Rows (y + dy, z + dz), dy 0..2, dz 0..1, of n points from x0. */
static void qs_rows(qs_grid g, __global const float *dens, int x0, int y, int z, int n,
                    uint r[2][3])
{
    for (int dz = 0; dz < 2; dz++)
        for (int dy = 0; dy < 3; dy++) r[dz][dy] = qs_row(g, dens, x0, y + dy, z + dz, n);
}

/* Vertices are made for the points of planes (z0, z1], and of plane 0 in the first slab;
 * triangles for the cells of layers [z0, z1). */
static int qs_makes_vertices(qs_grid g, int z)
{
    return z > g.z0 || z == 0;
}

__kernel __attribute__((reqd_work_group_size(2, 8, 8)))
void qs_count(__global const float *dens, int4 dims, int4 span, float iso,
              __constant uchar *ntri, __global uint2 *counts)
{
    qs_grid g = qs_grid_of(dims, span, iso);
    int ix = get_global_id(0), y = get_global_id(1), z = g.z0 + get_global_id(2), x0 = 4 * ix;
    if (ix >= g.nix || y >= g.ny || z > g.z1) return;
    uint nv = 0, nt = 0;
    if (qs_makes_vertices(g, z)) {
        qs_edges e = qs_edges_of(g, dens, x0, y, z);
        nv = popcount(e.x) + popcount(e.y) + popcount(e.z);
    }
    if (z < g.z1 && y + 1 < g.ny) {
        uint r[2][3], cells = qs_with_next(g, x0, 4);
        qs_rows(g, dens, x0, y, z, 5, r);
        for (int i = 0; i < 4; i++)
            if (cells >> i & 1) nt += ntri[qs_cube(r, i)];
    }
    counts[qs_item(g, ix, y, z)] = (uint2)(nv, nt);
}

/* Exclusive prefix sums of (vertex, triangle) counts: each work-group scans 4 * its size
 * values in place and leaves their total in sums[group]; qs_scan_add then adds the scanned
 * totals of the groups before. */
__kernel void qs_scan(__global uint2 *data, uint n, __global uint2 *sums, __local uint2 *tmp)
{
    size_t lid = get_local_id(0), ls = get_local_size(0);
    size_t base = 4 * get_global_id(0);
    uint2 v[4], run = (uint2)(0, 0);
    for (int k = 0; k < 4; k++) {
        uint2 c = base + k < n ? data[base + k] : (uint2)(0, 0);
        v[k] = run;
        run += c;
    }
    tmp[lid] = run;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (size_t off = 1; off < ls; off <<= 1) {
        uint2 add = lid >= off ? tmp[lid - off] : (uint2)(0, 0);
        barrier(CLK_LOCAL_MEM_FENCE);
        tmp[lid] += add;
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    uint2 before = lid > 0 ? tmp[lid - 1] : (uint2)(0, 0);
    for (int k = 0; k < 4; k++)
        if (base + k < n) data[base + k] = v[k] + before;
    if (lid == ls - 1) sums[get_group_id(0)] = tmp[lid];
}

__kernel void qs_scan_add(__global uint2 *data, uint n, uint per, __global const uint2 *sums)
{
    size_t i = get_global_id(0);
    if (i < n) data[i] += sums[i / per];
}

/* Quantization as the host's (qsurf.h): signed normals of 8 bits, colours of 8 bits, both
 * rounded half away from zero. */
static int qs_round(float v)
{
    return v >= 0.0f ? (int)(v + 0.5f) : -(int)(0.5f - v);
}

static char qs_snorm8(float f)
{
    float v = f * 127.5f - 0.5f;
    return (char)(!(v > -128.0f) ? -128 : v >= 127.0f ? 127 : qs_round(v));
}

static uchar qs_unorm8(float f)
{
    float v = f * 255.0f;
    return (uchar)(!(v > 0.0f) ? 0 : v >= 255.0f ? 255 : qs_round(v));
}

/* Density gradient at a grid point in index space: central differences, one-sided at the
 * volume's faces. */
static float3 qs_gradient(qs_grid g, __global const float *dens, int x, int y, int z)
{
    int c[3] = {x, y, z}, n[3] = {g.nx, g.ny, g.nz};
    size_t step[3] = {1, (size_t)g.nx, (size_t)g.nx * g.ny}, at = qs_at(g, x, y, z);
    float r[3];
    for (int d = 0; d < 3; d++) {
        int lo = c[d] > 0, hi = c[d] + 1 < n[d];
        r[d] = lo + hi ? (dens[at + hi * step[d]] - dens[at - lo * step[d]]) / (float)(lo + hi)
                       : 0.0f;
    }
    return (float3)(r[0], r[1], r[2]);
}

typedef struct qs_out {
    __global float *pos;
    __global char *normal;
    __global uchar *color;
} qs_out;

typedef struct qs_tex {
    __global const float *dens, *rgb[3];
    int colored;
    float4 solid;
} qs_tex;

/* The colour at t between grid points a and b: the texture interpolated, renormalised
 * when brighter than 1; or the solid colour. */
static void qs_color(qs_grid g, const qs_tex *tx, size_t a, size_t b, float t,
                     __global uchar *out)
{
    float c[3] = {tx->solid.x, tx->solid.y, tx->solid.z}, m = 1.0f;
    for (int k = 0; tx->colored && k < 3; k++) {
        float u = tx->rgb[k][a], w = tx->rgb[k][b];
        c[k] = u + t * (w - u);
        m = max(m, c[k]);
    }
    for (int k = 0; k < 3; k++) out[k] = qs_unorm8(c[k] / m);
    out[3] = 255;
}

/* Vertex v on the edge from point (x, y, z) along `axis` (x +1, y +1, z -1). */
static void qs_emit(qs_grid g, const qs_tex *tx, float4 origin, qs_out o, uint v, int x,
                    int y, int z, int axis)
{
    int p[3] = {x, y, z}, q[3] = {x, y, z};
    q[axis] += axis == 2 ? -1 : 1;
    size_t a = qs_at(g, x, y, z), b = qs_at(g, q[0], q[1], q[2]);
    float d0 = tx->dens[a], d1 = tx->dens[b];
    float t = (g.iso - d0) / (d1 - d0), o3[3] = {origin.x, origin.y, origin.z};
    float3 g0 = qs_gradient(g, tx->dens, x, y, z), g1 = qs_gradient(g, tx->dens, q[0], q[1], q[2]);
    float3 n = g0 + t * (g1 - g0);
    float len = sqrt(dot(n, n)), nv[3] = {n.x, n.y, n.z};
    for (int r = 0; r < 3; r++) {
        o.pos[3 * v + r] = o3[r] + ((float)p[r] + t * (float)(q[r] - p[r])) * origin.w;
        o.normal[3 * v + r] = qs_snorm8(len > 0.0f ? -nv[r] / len : r == 2 ? 1.0f : 0.0f);
    }
    qs_color(g, tx, a, b, t, o.color + 4 * v);
}

/* origin = (x, y, z, spacing); vfirst: the mesh index of the slab's first vertex. Writes
 * the slab's vertices from 0 and each point's first vertex (a mesh index) into vbase,
 * which holds planes z0..z1. */
/* origin = (x, y, z, spacing); vfirst: the mesh index of the slab's first vertex. Writes
 * the slab's vertices from 0 and each point's first vertex (a mesh index) into vbase,
 * which holds planes z0..z1. */
__kernel __attribute__((reqd_work_group_size(2, 8, 8)))
void qs_vertices(__global const float *dens, __global const float *red,
                 __global const float *green, __global const float *blue, int4 dims,
                 int4 span, float iso, float4 origin, int colored, float4 solid,
                 __global const uint2 *first, uint vfirst, __global uint *vbase,
                 __global float *pos, __global char *normal, __global uchar *color)
{
    qs_grid g = qs_grid_of(dims, span, iso);
    int ix = get_global_id(0), y = get_global_id(1), z = g.z0 + get_global_id(2), x0 = 4 * ix;
    if (ix >= g.nix || y >= g.ny || z > g.z1 || !qs_makes_vertices(g, z)) return;
    qs_edges e = qs_edges_of(g, dens, x0, y, z);
    uint any = e.x | e.y | e.z, bits[3] = {e.x, e.y, e.z};
    if (!any) return;
    qs_tex tx = {dens, {red, green, blue}, colored, solid};
    qs_out o = {pos, normal, color};
    uint v = first[qs_item(g, ix, y, z)].x;
    for (int i = 0; i < 4; i++) {
        if (!(any >> i & 1)) continue;
        vbase[((size_t)(z - g.z0) * g.ny + y) * g.nx + x0 + i] = vfirst + v;
        for (int axis = 0; axis < 3; axis++)
            if (bits[axis] >> i & 1) qs_emit(g, &tx, origin, o, v++, x0 + i, y, z, axis);
    }
}

/* The vertex on edge e of cell x0 + i: its owner point's first vertex plus the owner's
 * crossing edges before it (x, then y, then z), from the rows r around the cell. */
static uint qs_edge_vertex(qs_grid g, const uint r[2][3], __global const uint *vbase,
                           __constant uchar *edge_from, int x0, int i, int y, int z, int e)
{
    int from = edge_from[e], axis = e >> 2;
    int dx = from & 1, dy = from >> 1 & 1, dz = (from >> 2 & 1) + (axis == 2), p = i + dx;
    uint row = r[dz][dy], rank = 0;
    if (axis > 0) rank += (row ^ row >> 1) >> p & 1 & (x0 + p + 1 < g.nx);
    if (axis > 1) rank += (row ^ r[dz][dy + 1]) >> p & 1 & (y + dy + 1 < g.ny);
    return vbase[((size_t)(z + dz - g.z0) * g.ny + y + dy) * g.nx + x0 + p] + rank;
}

__kernel __attribute__((reqd_work_group_size(2, 8, 8)))
void qs_triangles(__global const float *dens, int4 dims, int4 span, float iso,
                  __constant uchar *ntri, __constant uchar *tri, __constant uchar *edge_from,
                  __global const uint2 *first, __global const uint *vbase, __global uint *index)
{
    qs_grid g = qs_grid_of(dims, span, iso);
    int ix = get_global_id(0), y = get_global_id(1), z = g.z0 + get_global_id(2), x0 = 4 * ix;
    if (ix >= g.nix || y + 1 >= g.ny || z >= g.z1) return;
    uint r[2][3], cells = qs_with_next(g, x0, 4);
    qs_rows(g, dens, x0, y, z, 6, r);
    __global uint *out = index + 3 * (size_t)first[qs_item(g, ix, y, z)].y;
    for (int i = 0; i < 4; i++) {
        if (!(cells >> i & 1)) continue;
        uint cube = qs_cube(r, i);
        for (int k = 0; k < 3 * ntri[cube]; k++)
            *out++ = qs_edge_vertex(g, r, vbase, edge_from, x0, i, y, z,
                                    tri[cube * 3 * QS_MAXTRI + k]);
    }
}
