/* qsurf_impl.h: what the QuickSurf files share inside src/surf (not a public API): the
 * fast exp2, the atom table sorted into the acceleration grid, the slab buffers, the CPU
 * density loops, the slab planner, marching cubes over streamed slabs, and the OpenCL
 * engine. */
#ifndef MS_QSURF_IMPL_H
#define MS_QSURF_IMPL_H

#include "surf/qsurf.h"

#include <string.h>

/* ---------------------------------------------------------------- fast exp2
 * 2^e for e <= 0 as 2^floor(e) * p(f), f = e - floor(e) in [0, 1), p a degree-4 polynomial
 * fitted to 2^f for minimum relative error (2.6e-6; VMD's is 1.3e-3; a Gaussian, the
 * product of three, is within 9e-6 of exp() on 1tii). The CPU loops and the OpenCL kernel
 * evaluate it with the same fused multiply-adds, so their sums agree bit for bit. */
#define MS_QSURF_EXP2_C0 1.0000026f
#define MS_QSURF_EXP2_C1 0.693003809f
#define MS_QSURF_EXP2_C2 0.2414428f
#define MS_QSURF_EXP2_C3 0.0520114807f
#define MS_QSURF_EXP2_C4 0.0135341212f
#define MS_QSURF_LOG2E 1.44269504088896340736f

/* The approximation for one value (e below -126 counts as -126). */
static inline float ms_qsurf_exp2_1(float e)
{
    e = e < -126.0f ? -126.0f : e;
    float fl = floorf(e), f = e - fl;
    float p = fmaf(fmaf(fmaf(fmaf(MS_QSURF_EXP2_C4, f, MS_QSURF_EXP2_C3), f,
                             MS_QSURF_EXP2_C2), f, MS_QSURF_EXP2_C1), f, MS_QSURF_EXP2_C0);
    int32_t bits;
    memcpy(&bits, &p, sizeof bits);
    bits += (int32_t)fl * (1 << 23);
    memcpy(&p, &bits, sizeof p);
    return p;
}
float ms_qsurf_exp2(float e);

/* The Gaussian is separable: an atom's value at a voxel is the product of its factors
 * along the three axes, exp2(w dx^2) * (exp2(w dy^2) * exp2(w dz^2)), in that order in every
 * loop. Per-axis factors are computed once per atom and row, leaving a multiply per voxel;
 * the cutoff is tested on the full squared distance w (dx^2 + dy^2 + dz^2) >= elim. */
static inline float ms_qsurf_factor(float w, float d)
{
    return ms_qsurf_exp2_1(w * (d * d));
}

/* ---------------------------------------------------------------- acceleration grid
 * The atoms in grid units (voxel index space), sorted by cell, cells z-major, so the atoms
 * of a z range of cells are one contiguous run. Cells are at least one cutoff wide. */
typedef struct ms_qsurf_atomgrid {
    size_t n;
    float *xyzw;             /* 4 per atom: x y z, w = -log2(e) h^2 / (2 sigma^2) */
    float *rgb;              /* 4 per atom: colour / iso, 0; NULL when solid */
    uint32_t *cellstart;     /* ncells + 1 */
    int nc[3];
    float cw[3];             /* cell width (grid units) */
    float cutmax;            /* the largest cutoff radius (grid units) */
    float *scratch;          /* per thread: scratch_n floats for the per-axis factors */
    size_t scratch_n;        /* ms_qsurf_scratch_floats */
    float elim;              /* w d^2 below this is beyond the cutoff: -gausslim^2 log2(e) / 2 */
} ms_qsurf_atomgrid;

/* Planes of a density block (at most). */
#define MS_QSURF_BLOCK_PLANES 8
/* Floats of a thread's scratch for a grid of n[0] x n[1] points: per-axis factors of an
 * atom's x window (and its x distances), y rows and z planes in a block, each run padded
 * by whole vectors. */
static inline size_t ms_qsurf_scratch_floats(const int n[3])
{
    return 2 * ((size_t)n[0] + 16) + (size_t)n[1] + 16 + MS_QSURF_BLOCK_PLANES + 16;
}

int ms_qsurf_atomgrid_build(const ms_qsurf_atoms *a, const ms_qsurf_grid *g,
                            ms_qsurf_atomgrid *ag, ms_error *err);
void ms_qsurf_atomgrid_free(ms_qsurf_atomgrid *ag);
/* Cells per axis for a grid, and the bytes the table will take. */
void ms_qsurf_atomgrid_cells(const ms_qsurf_grid *g, int nc[3]);
size_t ms_qsurf_atomgrid_bytes(const ms_qsurf_grid *g, int colored);
/* Whether an atom can contribute: finite coordinates and a positive finite radius. */
static inline int ms_qsurf_atom_ok(const float *xyz, float r)
{
    return isfinite(xyz[0]) && isfinite(xyz[1]) && isfinite(xyz[2]) && r > 0.0f && isfinite(r);
}
/* Input atom k's index into the arrays. */
static inline size_t ms_qsurf_atom_index(const ms_qsurf_atoms *a, size_t k)
{
    return a->index ? a->index[k] : k;
}
/* The reach (grid units) along one axis of a squared radius r2: its square root, a hair
 * larger so that rounding never leaves out a voxel the cutoff test would take. */
static inline float ms_qsurf_reach(float r2)
{
    return sqrtf(r2) * 1.0001f + 1e-4f;
}

/* Cell index of atom coordinates (grid units). */
static inline int ms_qsurf_cell_of(float x, float w, int n)
{
    int c = (int)(x / w);
    return c < 0 ? 0 : c >= n ? n - 1 : c;
}

/* ---------------------------------------------------------------- slab buffers
 * Planes zb..ze of the density map and colour texture, x fastest. Planes zb..cz-1 were
 * kept from the previous slab; the density loops compute planes cz..ze. */
typedef struct ms_qsurf_slab {
    int nx, ny, zb, ze, cz;
    float *dens;
    float *rgb[3];           /* NULL when solid */
} ms_qsurf_slab;

/* ---------------------------------------------------------------- CPU density */
enum {
    MS_QSURF_K_SCATTER = 0,  /* per atom, over the voxels within its cutoff */
    MS_QSURF_K_GATHER = 1,   /* per voxel, over the atoms of the neighbouring cells */
    MS_QSURF_K_PLAIN = 0,    /* plain C */
    MS_QSURF_K_SIMD = 2      /* AVX2 + FMA (x86-64, chosen at run time) */
};

/* Zero planes cz..ze of the slab and sum the atoms' Gaussians into them, on all cores,
 * with the loop chosen by ms_qsurf_cpu_kernel(). */
void ms_qsurf_density_cpu(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s);
/* The same with an explicit loop (MS_QSURF_K_* flags); SIMD falls back to plain where the
 * CPU lacks it. */
void ms_qsurf_density_cpu_with(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, int kernel);
/* The default loop: SIMD scatter unless MOLSCOPE_NOSIMD or MOLSCOPE_QUICKSURF_KERNEL say
 * otherwise. */
int ms_qsurf_cpu_kernel(void);
const char *ms_qsurf_kernel_name(int kernel);
/* 1 when this CPU runs the SIMD loops. */
int ms_qsurf_have_simd(void);

/* A block of a slab, small enough to stay in cache while its atoms are added: planes
 * z0..z1 and rows y0..y1, inclusive. */
typedef struct ms_qsurf_block {
    int z0, z1, y0, y1;
    float *scratch;          /* the running thread's scratch (ms_qsurf_atomgrid) */
} ms_qsurf_block;

/* The cells whose atoms can reach the block: cz in [lo[1], hi[1]], cy in [lo[0], hi[0]],
 * every cx (a contiguous run of the table per (cz, cy)). */
static inline void ms_qsurf_block_cells(const ms_qsurf_atomgrid *ag, const ms_qsurf_block *b,
                                        int lo[2], int hi[2])
{
    lo[0] = ms_qsurf_cell_of((float)b->y0 - ag->cutmax, ag->cw[1], ag->nc[1]);
    hi[0] = ms_qsurf_cell_of((float)b->y1 + ag->cutmax, ag->cw[1], ag->nc[1]);
    lo[1] = ms_qsurf_cell_of((float)b->z0 - ag->cutmax, ag->cw[2], ag->nc[2]);
    hi[1] = ms_qsurf_cell_of((float)b->z1 + ag->cutmax, ag->cw[2], ag->nc[2]);
}

/* Loops of one kind over a block of the slab (already zeroed); the driver in density.c
 * calls them from the worker threads. */
void ms_qsurf_scatter_plain(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b);
void ms_qsurf_gather_plain(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b);
void ms_qsurf_scatter_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b);
void ms_qsurf_gather_avx2(const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s, const ms_qsurf_block *b);

/* Marching cubes' inside bits of a row: bit b of out[w] = d[64 w + b] > iso. */
void ms_qsurf_inside_bits_plain(const float *d, int n, float iso, uint64_t *out);
void ms_qsurf_inside_bits_avx2(const float *d, int n, float iso, uint64_t *out);

/* ---------------------------------------------------------------- memory planner */

/* The budget of the whole working set (atom table, slabs, extractor scratch and the mesh):
 * p->memlimit, else MOLSCOPE_QUICKSURF_MEMLIMIT, else the available memory (/proc/meminfo,
 * or sysinfo). The slabs are planned within half of it (ms_qsurf_plan_slabs), so the mesh
 * has the other half at least. */
size_t ms_qsurf_budget(const ms_qsurf_params *p);
/* Parse a byte count with an optional K/M/G suffix; 0 when malformed. */
size_t ms_qsurf_parse_bytes(const char *s);

typedef struct ms_qsurf_plan {
    int layers;              /* cell layers per slab: all of them, or a multiple of 8 */
    int nslabs;
    size_t bytes;            /* planned working set */
} ms_qsurf_plan;

/* Largest slab (at most maxlayers, 0 = no limit) whose working set fits half the budget
 * (the rest is the mesh's), kept near 192 MB when the budget is larger. Fails with a
 * message giving the bytes an 8-layer slab needs when even that does not fit. */
int ms_qsurf_plan_slabs(const ms_qsurf_grid *g, int colored, size_t budget, int maxlayers,
                        ms_qsurf_plan *pl, ms_error *err);
/* Bytes of the slab buffers alone (density, colour texture) holding `planes` planes. */
size_t ms_qsurf_slab_bytes(int nx, int ny, int planes, int colored);
int ms_qsurf_slab_alloc(ms_qsurf_slab *s, int nx, int ny, int planes, int colored);
void ms_qsurf_slab_free(ms_qsurf_slab *s);

/* ---------------------------------------------------------------- marching cubes
 * The cube case tables, built once from a face rule (diagonal inside corners of a face are
 * kept apart), so that neighbouring cells always agree and every surface is closed. Edge e
 * of a cell runs along axis e / 4 from the corner with offsets ms_qsurf_mc_edge_from[e];
 * corner c has offsets (c & 1, c >> 1 & 1, c >> 2 & 1). */
#define MS_QSURF_MC_MAXTRI 8
typedef struct ms_qsurf_mctab {
    uint8_t ntri[256];
    uint8_t tri[256][3 * MS_QSURF_MC_MAXTRI];
    /* The same triangles through each case's distinct edges: corner k of the case's
     * triangles is edge edges[case][corner[case][k]]. */
    uint8_t nedge[256], edges[256][12], corner[256][3 * MS_QSURF_MC_MAXTRI];
    /* Where edge e's vertex is found from its cell: bit 0 the owner point's x offset, bits
     * 1-2 its row (dy + 2 dz), bits 3-4 the edge's axis. */
    uint8_t owner[12];
    int bad;                 /* loops the rule could not triangulate (none: tested) */
} ms_qsurf_mctab;
const ms_qsurf_mctab *ms_qsurf_mc_table(void);
extern const uint8_t ms_qsurf_mc_edge_from[12];   /* corner where edge e starts */

/* Marching cubes over a volume delivered in slabs, bottom to top. Each grid point owns the
 * edges to its +x and +y neighbours and to its -z neighbour; a slab of cell layers
 * [z0, z1) makes the vertices of the points in planes (z0, z1] (and plane 0 in the first
 * slab), so the vertices of the plane two slabs share are made once and kept for the
 * next slab (whose buffers keep that plane's density too, see qsurf.c). Rows of points
 * are held as bitsets, 64 points a word. Output order depends only on the grid: vertices
 * by owner point, triangles by cell. */
typedef struct ms_qsurf_extract {
    int n[3], words;         /* words: 64-bit words per row */
    float iso;
    double origin[3], axis[3][3], gradm[3][3];   /* gradm = inverse transpose of axis */
    int aligned;             /* the axes run along x, y and z */
    int colored;
    float solid[3];
    int maxlayers;
    uint32_t *vbase;         /* per point of planes z0..z1 with crossing edges: first vertex */
    uint64_t *bits;          /* per row of planes z0..z1: inside, then crossing x, y, -z */
    uint32_t *vrow, *trow;   /* per row (+1): vertex and triangle counts, then first indices */
    int next_z0;             /* the slab expected next */
    ms_qsurf_mesh *mesh;
    size_t budget;           /* the surface's memory budget; 0: the mesh may grow freely */
    size_t mesh_room;        /* what the budget leaves the mesh, after the planned slabs */
    int over_budget;         /* the mesh did not fit mesh_room: the surface fails */
} ms_qsurf_extract;

int ms_qsurf_extract_begin(ms_qsurf_extract *mc, const int n[3], const float origin[3],
                           const float axis[3][3], float iso, int colored, const float solid[3],
                           int maxlayers, ms_qsurf_mesh *mesh, ms_error *err);
/* Extract layers [z0, z1): the slab must hold planes max(z0-1, 0) .. min(z1+1, nz-1). */
int ms_qsurf_extract_slab(ms_qsurf_extract *mc, const ms_qsurf_slab *s, int z0, int z1,
                          ms_error *err);
void ms_qsurf_extract_end(ms_qsurf_extract *mc);
/* Take over at slab z0 > 0 from the OpenCL path, which made the mesh up to plane z0 in this
 * extractor's order: plane z0's bits and first vertices are rebuilt from the slab's
 * density (it must hold planes z0 - 1 and z0) and the mesh's vertex count. */
int ms_qsurf_extract_resume(ms_qsurf_extract *mc, const ms_qsurf_slab *s, int z0,
                            ms_error *err);
/* Working memory of the extractor for slabs of `layers` layers. */
size_t ms_qsurf_extract_bytes(int nx, int ny, int layers);

/* Resize the mesh arrays to nv vertices and nt triangles (contents kept). On failure the
 * mesh keeps its old sizes and stays valid. */
int ms_qsurf_mesh_resize(ms_qsurf_mesh *m, size_t nv, size_t nt);
/* Can the extractor's mesh grow to nv vertices and nt triangles within mc->mesh_room? -1
 * (err naming the budget, mc->over_budget set) when not. */
int ms_qsurf_mesh_fits(ms_qsurf_extract *mc, size_t nv, size_t nt, ms_error *err);

/* ---------------------------------------------------------------- OpenCL engine
 * One engine per process (built kernels on the device, context and queue of cl/cl.h, which
 * the OpenCL tracer shares), shared by every surface and used by one surface at a time. A slab runs on the device from density to mesh: its
 * density stays there, marching cubes runs there, and only the mesh comes back, appended
 * to the host mesh in the host extractor's order (the same mesh, index for index). */
typedef struct ms_qsurf_cl ms_qsurf_cl;

/* Lock the engine, starting it on first use. any_type: accept a CPU device; otherwise
 * only a GPU or accelerator (unless MOLSCOPE_OPENCL_DEVICE names one). NULL with the
 * reason in err when there is none; *absent is then 1 when OpenCL is missing or has
 * no suitable device, 0 when a device failed. */
ms_qsurf_cl *ms_qsurf_cl_acquire(int any_type, int *absent, ms_error *err);
void ms_qsurf_cl_release(ms_qsurf_cl *cl);
/* Most cell layers per slab the device memory holds for this grid (0: none). */
int ms_qsurf_cl_max_layers(ms_qsurf_cl *cl, const ms_qsurf_grid *g, int colored);
/* Upload the atom table and make the buffers for slabs of up to `layers` cell layers of
 * nx x ny points. */
int ms_qsurf_cl_upload(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, int nx, int ny,
                       int layers, ms_error *err);
/* Slab [z0, z1) on the device: the density of planes s->zb..s->ze (planes the device
 * still holds from the slab before are kept), then marching cubes as
 * ms_qsurf_extract_slab would, the vertices and triangles appended to mc->mesh. The host
 * slab's buffers are not touched. t[0], t[1]: seconds of density and of marching cubes.
 * On any error the mesh is left as it was. */
int ms_qsurf_cl_slab(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, const ms_qsurf_slab *s,
                     ms_qsurf_extract *mc, int z0, int z1, double t[2], ms_error *err);
const char *ms_qsurf_cl_device_name(const ms_qsurf_cl *cl);
/* Fault injection for the tests: when >= 0, the slab after this many fails at stage
 * ms_qsurf_cl_fail_stage as a device error would (then the counter is off again). */
enum {
    MS_QSURF_CL_FAIL_DENSITY,    /* the density kernel */
    MS_QSURF_CL_FAIL_ALLOC,      /* growing the mesh buffers (out of device memory) */
    MS_QSURF_CL_FAIL_READ        /* reading the triangles back, after the vertices */
};
extern int ms_qsurf_cl_fail_after, ms_qsurf_cl_fail_stage;

#endif
