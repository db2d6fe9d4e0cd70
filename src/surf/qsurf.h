/* qsurf.h: QuickSurf, the Gaussian density surface engine, and its parts.
 *
 * A density map rho(p) = sum_i exp(-|p - x_i|^2 / 2 sigma_i^2), sigma_i = radscale * r_i, is
 * summed on a regular grid laid out by VMD's rules (padding, origin, N per axis, the
 * coarse-grained spacing rule, a cutoff of gausslim sigma per quality level), together
 * with a colour texture T(p) = sum_i (g_i(p) / iso) c_i. The volume is computed in slabs of
 * planes sized from a memory budget planned before any allocation, on the CPU (all cores,
 * SIMD) or on an OpenCL device (falling back to the CPU on any error), and marching cubes
 * turns each slab into one indexed mesh with shared vertices, seamless across slabs.
 *
 * The parts are public for the features that reuse them: the density map alone (volmap
 * density), marching cubes on any float grid (Isosurface), and the bead reduction (one
 * particle per residue) for cellular-scale systems.
 *
 * Environment: MOLSCOPE_QUICKSURF_MEMLIMIT=bytes (K, M, G suffixes) sets the memory budget
 * (the whole working set: the slabs are planned within half of it, the mesh must fit the
 * rest or the surface fails saying so),
 * MOLSCOPE_NOOPENCL turns the OpenCL path off, MOLSCOPE_OPENCL_DEVICE=index|name picks a
 * device, MOLSCOPE_NOSIMD forces the plain C density loops,
 * MOLSCOPE_QUICKSURF_KERNEL=gather|scatter picks the CPU density loop (for measurements). */
#ifndef MS_QSURF_H
#define MS_QSURF_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "base/base.h"

/* ---------------------------------------------------------------- mesh storage types
 * Compile-time switches, so that other precisions can be built and measured:
 *   MS_QSURF_POS_TYPE     float (default) or double
 *   MS_QSURF_NORMAL_TYPE  int8_t (default), int16_t or float
 *   MS_QSURF_COLOR_TYPE   uint8_t (default), uint16_t or float
 * Integer normals are quantized as in the OpenGL 1.2.1 spec, table 2.6: f = (2c + 1) / (2^b - 1);
 * integer colours as c / (2^b - 1). */
#ifndef MS_QSURF_POS_TYPE
#define MS_QSURF_POS_TYPE float
#endif
#ifndef MS_QSURF_NORMAL_TYPE
#define MS_QSURF_NORMAL_TYPE int8_t
#endif
#ifndef MS_QSURF_COLOR_TYPE
#define MS_QSURF_COLOR_TYPE uint8_t
#endif
typedef MS_QSURF_POS_TYPE ms_qsurf_pos_t;
typedef MS_QSURF_NORMAL_TYPE ms_qsurf_normal_t;
typedef MS_QSURF_COLOR_TYPE ms_qsurf_color_t;

/* Round to the nearest integer, halves away from zero (inline, no libm call, no branch:
 * v - 0.5 is -(0.5 - v) exactly, and truncation is symmetric). */
static inline long ms_qsurf_round(float v)
{
    return (long)(v + copysignf(0.5f, v));
}

/* Quantize f in [-1, 1] to a signed integer of half-range `half` (127.5 for 8 bits):
 * NaN and values below the range give the lowest code, values above it the highest. */
static inline long ms_qsurf_snorm(float f, float half)
{
    float hi = half - 0.5f, v = f * half - 0.5f;
    v = v > -hi - 1.0f ? v : -hi - 1.0f;
    return ms_qsurf_round(v < hi ? v : hi);
}

/* Quantize f in [0, 1] to an unsigned integer of maximum `max` (NaN gives 0). */
static inline long ms_qsurf_unorm(float f, float max)
{
    float v = f * max;
    v = v > 0.0f ? v : 0.0f;
    return ms_qsurf_round(v < max ? v : max);
}

static inline ms_qsurf_normal_t ms_qsurf_pack_normal(float f)
{
    return _Generic((ms_qsurf_normal_t)0,
        int8_t: (ms_qsurf_normal_t)ms_qsurf_snorm(f, 127.5f),
        int16_t: (ms_qsurf_normal_t)ms_qsurf_snorm(f, 32767.5f),
        default: (ms_qsurf_normal_t)f);
}

static inline float ms_qsurf_unpack_normal(ms_qsurf_normal_t c)
{
    return _Generic((ms_qsurf_normal_t)0,
        int8_t: (2.0f * (float)c + 1.0f) / 255.0f,
        int16_t: (2.0f * (float)c + 1.0f) / 65535.0f,
        default: (float)c);
}

static inline ms_qsurf_color_t ms_qsurf_pack_color(float f)
{
    return _Generic((ms_qsurf_color_t)0,
        uint8_t: (ms_qsurf_color_t)ms_qsurf_unorm(f, 255.0f),
        uint16_t: (ms_qsurf_color_t)ms_qsurf_unorm(f, 65535.0f),
        default: (ms_qsurf_color_t)f);
}

static inline float ms_qsurf_unpack_color(ms_qsurf_color_t c)
{
    return _Generic((ms_qsurf_color_t)0,
        uint8_t: (float)c / 255.0f,
        uint16_t: (float)c / 65535.0f,
        default: (float)c);
}

/* ---------------------------------------------------------------- the mesh
 * An indexed triangle mesh with shared vertices: each vertex is used by all the triangles
 * around it. Triangles are counter-clockwise seen from outside (from lower density);
 * normals point outwards. The arrays are plain malloc blocks a caller may adopt. */
/* The vertex arrays hold nv + 1 vertices (the last one spare, so that a display list can
 * hand pos to Embree, which reads 16 bytes per vertex, without a copy): MS_QSURF_MESH_VCAP
 * is the capacity in vertices of a mesh whose arrays exist. */
typedef struct ms_qsurf_mesh {
    size_t nv, nt;
    ms_qsurf_pos_t *pos;          /* 3 * nv: x y z */
    ms_qsurf_normal_t *normal;    /* 3 * nv */
    ms_qsurf_color_t *color;      /* 4 * nv: r g b a */
    uint32_t *index;              /* 3 * nt */
} ms_qsurf_mesh;

#define MS_QSURF_MESH_VCAP(m) ((m)->pos ? (m)->nv + 1 : 0)

void ms_qsurf_mesh_free(ms_qsurf_mesh *m);
/* Bytes held by the mesh arrays; per vertex (attributes only) and in all. */
size_t ms_qsurf_mesh_bytes(const ms_qsurf_mesh *m);
#define MS_QSURF_VERTEX_BYTES \
    (3 * sizeof(ms_qsurf_pos_t) + 3 * sizeof(ms_qsurf_normal_t) + 4 * sizeof(ms_qsurf_color_t))
/* Total triangle area (double precision). */
double ms_qsurf_mesh_area(const ms_qsurf_mesh *m);

/* ---------------------------------------------------------------- input and parameters */

/* The atoms of a surface. With `index`, atom k is atom index[k] of the arrays. Atoms with
 * a radius <= 0 or a non-finite coordinate are left out. */
typedef struct ms_qsurf_atoms {
    size_t n;
    const float *pos;        /* 3 per atom */
    const float *radius;     /* 1 per atom */
    const float *rgb;        /* 3 per atom in [0, 1], or NULL: every atom has `solid` */
    const uint32_t *index;   /* NULL: atoms 0..n-1 */
    float solid[3];
    /* The radius range VMD sizes the grid with (ms_qsurf_radius_range); 0 = the range of
     * these atoms. */
    float minrad, maxrad;
} ms_qsurf_atoms;

enum {
    MS_QSURF_AUTO = 0,       /* OpenCL on a GPU or accelerator device, else the CPU */
    MS_QSURF_CPU = 1,
    MS_QSURF_OPENCL = 2      /* any OpenCL device (PoCL on the CPU included), else the CPU */
};

typedef void (*ms_qsurf_notice_fn)(void *ctx, const char *msg);

typedef struct ms_qsurf_params {
    float radscale;          /* 1.0 */
    float isovalue;          /* 0.5 */
    float gridspacing;       /* 1.0 */
    int quality;             /* 0..3: gausslim 2.0 2.5 3.0 4.0 (others 2.0) */
    int backend;             /* MS_QSURF_AUTO, _CPU or _OPENCL */
    size_t memlimit;         /* bytes of the whole working set, mesh included; 0 =
                              * MOLSCOPE_QUICKSURF_MEMLIMIT, else the available memory */
    /* Where a fallback from OpenCL to the CPU is reported (once per process); NULL =
     * stderr. */
    ms_qsurf_notice_fn notice;
    void *notice_ctx;
} ms_qsurf_params;

void ms_qsurf_params_default(ms_qsurf_params *p);

/* VMD's radius range: min and max over all natoms radii, recomputed over the selected ones
 * (sel[0..nsel), or all when sel is NULL) when the minimum is <= 0.001 or max/min > 2.5. */
void ms_qsurf_radius_range(const float *radius, size_t natoms, const uint32_t *sel,
                           size_t nsel, float *minrad, float *maxrad);

/* ---------------------------------------------------------------- the grid
 * Voxel (i, j, k) has centre origin + (i, j, k) * h; x varies fastest in every array. */
typedef struct ms_qsurf_grid {
    int n[3];
    float origin[3];
    float h;                 /* spacing actually used (x minrad when minrad > 4 A) */
    float radscale, isovalue, gausslim, minrad, maxrad;
    float pad;               /* padding around the atoms' bounding box */
    size_t natoms;           /* atoms that contribute */
} ms_qsurf_grid;

/* Lay out the grid for these atoms and parameters (VMD's rules, doc/vmd-behaviour.md
 * section 7).
 * Returns -1 when no atom can contribute or the parameters are out of range. */
int ms_qsurf_grid_setup(const ms_qsurf_atoms *a, const ms_qsurf_params *p, ms_qsurf_grid *g,
                        ms_error *err);

/* ---------------------------------------------------------------- volumes */

/* A float grid for marching cubes. Point (i, j, k) is origin + i*axis[0] + j*axis[1] +
 * k*axis[2]; data holds n[0]*n[1]*n[2] values, x fastest. */
typedef struct ms_qsurf_volume {
    int n[3];
    float origin[3];
    float axis[3][3];        /* step vectors between neighbouring points along x, y, z */
    float *data;
    float *rgb[3];           /* optional colour grids (same layout), or NULL */
    float solid[3];          /* the colour when rgb[0] is NULL */
} ms_qsurf_volume;

void ms_qsurf_volume_free(ms_qsurf_volume *v);

/* The density map alone, over the whole grid of ms_qsurf_grid_setup: fills v (data, and
 * rgb unless the atoms have one solid colour; T is normalised by the isovalue). */
int ms_qsurf_density(const ms_qsurf_atoms *a, const ms_qsurf_params *p, ms_qsurf_volume *v,
                     ms_error *err);

/* Marching cubes on any volume at `iso`: inside is data > iso. Vertex colours are the
 * colour grids interpolated at the vertex (renormalised when brighter than 1), or the solid
 * colour. The mesh is replaced. */
int ms_qsurf_mc(const ms_qsurf_volume *v, float iso, ms_qsurf_mesh *out, ms_error *err);

/* ---------------------------------------------------------------- volmap density
 * VMD's `volmap density`: rho(p) = sum_i w_i N_i exp(-|p - x_i|^2 / 2 sigma_i^2) with
 * sigma_i = radscale r_i and N_i = 1 / ((2 pi)^(3/2) sigma_i^3), so that each atom's
 * Gaussian integrates to its weight (the map of an unweighted selection integrates to its
 * atom count, in atoms per cubic Angstrom). The grid is QuickSurf's for these atoms (spacing
 * res, padding from radscale and the largest radius); quality sets the cutoff as for
 * surfaces (3: 4 sigma). With use_box the grid covers box_lo..box_hi as well (so that the
 * maps of several frames share one grid). Atoms with radius <= 0 are left out. */
typedef struct ms_volmap_in {
    size_t n;
    const float *pos, *radius;   /* 3 and 1 per atom */
    const float *weight;         /* 1 per atom, or NULL for 1 */
    const uint32_t *index;       /* NULL: atoms 0..n-1 */
} ms_volmap_in;

typedef struct ms_volmap_params {
    float res, radscale;         /* 1.0, 1.0 */
    int quality;                 /* 3 */
    int use_box;
    float box_lo[3], box_hi[3];
} ms_volmap_params;

void ms_volmap_params_default(ms_volmap_params *p);
/* The map into *out (data only; axes orthogonal, spacing in axis[d][d]). */
int ms_volmap_density(const ms_volmap_in *in, const ms_volmap_params *p, ms_qsurf_volume *out,
                      ms_error *err);

/* ---------------------------------------------------------------- the whole surface */

typedef struct ms_qsurf_stats {
    ms_qsurf_grid grid;
    int nslabs, slab_layers;     /* slabs run and cell layers per slab */
    size_t budget, plan_bytes;   /* memory budget and the planned working set */
    double t_setup, t_density, t_mc;   /* seconds */
    int opencl;                  /* slabs whose density ran on the OpenCL device */
    const char *kernel;          /* the CPU density loop used: "avx2-scatter", ... */
    char note[512];              /* why OpenCL was not used, when it was asked for */
} ms_qsurf_stats;

/* Compute the surface of the atoms into *out (replaced). stats may be NULL. */
int ms_qsurf_surface(const ms_qsurf_atoms *a, const ms_qsurf_params *p, ms_qsurf_mesh *out,
                     ms_qsurf_stats *stats, ms_error *err);

/* Bytes the surface's working set needs (atom table, cell grid, slab buffers) with slabs of
 * `layers` cell layers, for a grid from ms_qsurf_grid_setup. A memory budget of twice this
 * plans slabs of that many layers (the mesh has the other half). */
size_t ms_qsurf_plan_bytes(const ms_qsurf_grid *g, int colored, int layers);

/* ---------------------------------------------------------------- beads
 * One particle per residue, as VMD's bead mode: at the unweighted centroid of the
 * residue's atoms among `a` (consecutive atoms with the same residue number), radius = the
 * largest distance of those atoms from the centroid + 1.0 A, colour = that of the
 * residue's last atom. residue[] is indexed like a->pos. */
typedef struct ms_qsurf_beads {
    size_t n;
    float *pos, *radius, *rgb;   /* rgb is NULL when the atoms had one solid colour */
    float solid[3];
} ms_qsurf_beads;

int ms_qsurf_beads_build(const ms_qsurf_atoms *a, const int32_t *residue, ms_qsurf_beads *out,
                         ms_error *err);
/* Point an ms_qsurf_atoms at the beads (no copy). */
void ms_qsurf_beads_atoms(const ms_qsurf_beads *b, ms_qsurf_atoms *a);
void ms_qsurf_beads_free(ms_qsurf_beads *b);

#endif
