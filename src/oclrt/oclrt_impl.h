/* oclrt_impl.h: what the files of the OpenCL tracer share (built with OpenCL):
 * the flat world (flatten.c: every primitive in world space, in the structure-of-arrays
 * layout the kernels read, params.h numbering the kinds), its BVH (bvh.c), and the engine
 * (device.c: the kernels on the shared device, context and queue of cl/cl.h). */
#ifndef MS_OCLRT_IMPL_H
#define MS_OCLRT_IMPL_H

#include <stdint.h>

#include "cl/cl.h"
#include "oclrt/oclrt.h"
#include "oclrt/params.h"
#include "rt/rt_common.h"

typedef struct orc_world {
    /* quadrics (spheres, cylinders, cones, rings): two float4 and (geometry, RGBA8, RGBA8,
     * float bits) each
     *   sphere: (centre, radius), unused; cylinder: (base, radius), (unit axis, length), and
     *   the colour beyond the joint with the joint's distance along the axis (a bond's);
     *   cone: (base, base radius), (apex, apex radius); ring: (centre, outer radius),
     *   (normal, inner radius); the second colour and distance unused but for cylinders */
    size_t nq;
    float *qa, *qb;
    uint32_t *qm, *qkind;
    /* triangles: three vertex indices and the geometry; vertices: float4 position, char4
     * normal as the display list stores it (quantized, in the list's coordinates), RGBA8 */
    size_t ntri, nverts;
    uint32_t *tri;
    float *vxyz;
    int8_t *vnorm;
    ms_rgba8 *vcol;
    /* geometries (one kind of one list): (ambient, diffuse, mirror, phong), (phong exponent,
     * opacity, outline, outline width), (angle-modulated, alpha varies, item, its item's
     * number of clip planes) */
    size_t ngeoms;
    float *gmat0, *gmat1;
    int32_t *gflag;
    /* items (placed lists): ORC_ITEM float4s each (params.h): the normal matrix and the
     * item's clip planes */
    size_t nitems, nclipped;    /* items, and those with clip planes */
    float *item;
    /* the BVH: per node the boxes of its two children and (child, child, count, count):
     * a count of 0 makes the child an inner node (or nothing when negative), else a leaf of
     * that many references from leaf[child] */
    size_t nnodes, nleaf;
    float *lo0, *hi0, *lo1, *hi1;
    int32_t *child;
    uint32_t *leaf;
    float eps;
    rt_sources set;             /* the scene's lists, their strokes and cap discs */
} orc_world;

/* The tree the builders make (bvh.c: Embree's rtcBuildBVH; sah.c: our own binned SAH
 * builder), which bvh.c flattens: binary, a leaf holding n references. */
typedef struct orc_box {
    float lo[3], hi[3];
} orc_box;
typedef struct orc_bnode {
    int leaf;
    uint32_t n, *refs;
    struct orc_bnode *kid[2];
    orc_box box[2];
} orc_bnode;
/* A primitive to build over: its box and its leaf reference. */
typedef struct orc_bprim {
    orc_box box;
    uint32_t ref;
} orc_bprim;
/* Our binned SAH builder over p[0..n) (reordered), leaves of at most max_leaf references
 * (more only below max_depth levels). The tree lives in *arena (orc_sah_free). NULL with
 * err set when memory runs out. */
orc_bnode *orc_sah_build(orc_bprim *p, size_t n, int max_leaf, int max_depth, void **arena,
                         ms_error *err);
void orc_sah_free(void *arena);

/* Flatten s into w. 0, or MS_OCLRT_EINPUT (bad input) / -1 (no memory) with err set. */
int orc_world_build(orc_world *w, const ms_scene *s, ms_error *err);
void orc_world_free(orc_world *w);
/* The BVH of w's primitives (Embree's builder, or ours when ms_oclrt_own_bvh is set or
 * there is no Embree). 0, or -1 with err set. */
int orc_bvh_build(orc_world *w, ms_error *err);

/* ---------------------------------------------------------------- the engine (device.c) */

typedef struct orc_engine {
    ms_cl_device dev;           /* the device, its memory and name */
    cl_context ctx;             /* the shared engine's (cl/cl.h), not released here */
    cl_command_queue queue;
    cl_program program;
    cl_kernel init, pass;
} orc_engine;

/* The engine, started on first use (the device chosen, the kernels built or read from the
 * cache), held until orc_engine_release. NULL with err set when OpenCL cannot render. */
orc_engine *orc_engine_acquire(ms_error *err);
void orc_engine_release(orc_engine *e);

#endif
