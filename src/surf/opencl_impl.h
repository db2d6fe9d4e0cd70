/* opencl_impl.h: what the two halves of QuickSurf's OpenCL path share (opencl.c: the
 * engine, its device, program and buffers; opencl_slab.c: one slab from density to mesh).
 * Only built with OpenCL. */
#ifndef MS_QSURF_OPENCL_IMPL_H
#define MS_QSURF_OPENCL_IMPL_H

#include "cl/cl.h"
#include "surf/qsurf_impl.h"

/* Levels of the prefix sum: each level holds the totals of 4 x (scan work-group size)
 * values of the level below; 8 levels cover any slab. */
#define MS_QSURF_CL_LEVELS 8

enum { K_DENSITY, K_COUNT, K_SCAN, K_SCAN_ADD, K_VERTICES, K_TRIANGLES, K_COUNT_OF };

struct ms_qsurf_cl {
    ms_cl_device dev;        /* the device, its type, memory and name */
    cl_context ctx;          /* the shared engine's (cl/cl.h), not released here */
    cl_command_queue queue;
    cl_program program;
    cl_kernel k[K_COUNT_OF];
    size_t scan_local;       /* work-group size of qs_scan */
    /* The surface being computed: atom table, cube tables, the slab's density and colour
     * planes, first vertices of planes z0..z1, the counts and their prefix-sum levels, and
     * the slab's mesh (grown as needed). */
    cl_mem atoms, colors, cells, ntri, tri, edge_from;
    cl_mem dens, rgb[3], vbase, level[MS_QSURF_CL_LEVELS];
    cl_mem pos, normal, color, index;
    size_t vcap, tcap;       /* vertices and triangles the mesh buffers hold */
    int nx, ny, planes, colored;
    int held_zb, held_ze;    /* planes of the grid the density buffers hold (none: ze < zb) */
    int fail_stage;          /* fault injection: the stage of this slab that fails, or -1 */
};

/* A buffer; nothing when *e already holds an error. */
cl_mem ms_qsurf_cl_buffer(ms_qsurf_cl *cl, cl_mem_flags flags, size_t bytes, const void *host,
                          cl_int *e);
void ms_qsurf_cl_free_mem(cl_mem *m);
/* Items of the count, vertex and triangle kernels per row (four points each). */
static inline int ms_qsurf_cl_items(int nx)
{
    return (nx + 3) / 4;
}

#endif
