/* opencl.c: the engine of QuickSurf's OpenCL path. One engine per process: the kernels of
 * kernels.cl on the process's one OpenCL device, context and queue, which the OpenCL tracer
 * shares (cl/cl.h: a GPU first, or the one MOLSCOPE_OPENCL_DEVICE names), built once (kept as a binary in the OpenCL cache of
 * cl/cl.h; PoCL keeps its own in POCL_CACHE_DIR, set here to a per-user folder when unset);
 * and the buffers of the surface being computed, sized from the device's memory.
 * opencl_slab.c runs the slabs. Every error is returned as a message; the caller falls back
 * to the CPU. Without OpenCL at build time these report its absence. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ms_qsurf_cl_fail_after = -1;
int ms_qsurf_cl_fail_stage = MS_QSURF_CL_FAIL_DENSITY;

#ifdef MS_HAVE_OPENCL
#include "surf/opencl_impl.h"

#include <pthread.h>

#define STR_(x) #x
#define STR(x) STR_(x)

static const char *kernel_source =
#include "src/surf/kernels.inc"
    ;

/* The exp2 polynomial and the cube tables' width, shared with the C code. */
static const char *build_options =
    "-DQS_C0=" STR(MS_QSURF_EXP2_C0) " -DQS_C1=" STR(MS_QSURF_EXP2_C1)
    " -DQS_C2=" STR(MS_QSURF_EXP2_C2) " -DQS_C3=" STR(MS_QSURF_EXP2_C3)
    " -DQS_C4=" STR(MS_QSURF_EXP2_C4) " -DQS_MAXTRI=" STR(MS_QSURF_MC_MAXTRI);

static const char *kernel_names[K_COUNT_OF] = {"qs_density", "qs_count", "qs_scan",
                                               "qs_scan_add", "qs_vertices", "qs_triangles"};

static pthread_mutex_t engine_lock = PTHREAD_MUTEX_INITIALIZER;
static ms_qsurf_cl engine;
static int engine_state;     /* 0 not started, 1 device found, 2 running, -1 failed */
static int engine_absent;
static char engine_failure[sizeof(ms_error)];

/* The shared engine's device (cl/cl.h), in QuickSurf's words when there is none. */
static int pick_device(ms_qsurf_cl *cl, ms_error *err)
{
    cl_int e;
    const char *want = NULL;
    ms_cl_engine *shared;
    int rc = ms_cl_engine_device(&shared, 0, &e, &want);
    if (rc == 0) {
        cl->dev = shared->dev;
        return 0;
    }
    engine_absent = 1;
    if (rc == MS_CL_NOPLATFORM)
        return ms_cl_fail(err, "clGetPlatformIDs (no OpenCL platform)", e);
    ms_error_set(err, want ? "OpenCL: no device matches MOLSCOPE_OPENCL_DEVICE=%s"
                           : "OpenCL: no device%s", want ? want : "");
    return -1;
}

/* The kernels, from the binary cache when it holds them (cl/cl.h), else from source. */
static int build_program(ms_qsurf_cl *cl, ms_error *err)
{
    char log[400];
    int rc = ms_cl_build(cl->ctx, cl->dev.id, kernel_source, build_options, "qsurf",
                         &cl->program, log, sizeof log, err);
    if (rc == MS_CL_EBUILD) {
        ms_error_set(err, "OpenCL: the QuickSurf kernels do not build on %s: %s", cl->dev.name,
                     log);
        return -1;
    }
    if (rc) return -1;
    for (int k = 0; k < K_COUNT_OF; k++) {
        cl_int e;
        cl->k[k] = clCreateKernel(cl->program, kernel_names[k], &e);
        if (e != CL_SUCCESS) return ms_cl_fail(err, "clCreateKernel", e);
    }
    return 0;
}

/* The prefix sum's work-group: a power of two up to 256 that the kernel allows. */
static int scan_group(ms_qsurf_cl *cl, ms_error *err)
{
    size_t most = 0;
    cl_int e = clGetKernelWorkGroupInfo(cl->k[K_SCAN], cl->dev.id, CL_KERNEL_WORK_GROUP_SIZE,
                                        sizeof most, &most, NULL);
    if (e != CL_SUCCESS) return ms_cl_fail(err, "clGetKernelWorkGroupInfo", e);
    for (cl->scan_local = 256; cl->scan_local > most; cl->scan_local /= 2) {}
    if (cl->scan_local < 32) {
        ms_error_set(err, "OpenCL: %s runs work-groups of %zu items only", cl->dev.name, most);
        return -1;
    }
    return 0;
}

/* The kernels on the shared context (made then if the tracer has not), the first time the
 * device is used. */
static int start(ms_qsurf_cl *cl, ms_error *err)
{
    ms_cl_engine *shared;
    cl_int e;
    const char *want;
    if (ms_cl_engine_device(&shared, 0, &e, &want) || ms_cl_engine_start(shared, err)) return -1;
    cl->ctx = shared->ctx;
    cl->queue = shared->queue;
    if (build_program(cl, err) < 0) return -1;
    return scan_group(cl, err);
}

/* The kernels write float positions, 8-bit normals and 8-bit colours. */
static int mesh_types_ok(void)
{
    return sizeof(ms_qsurf_pos_t) == 4 && (ms_qsurf_pos_t)0.5f != 0 &&
           sizeof(ms_qsurf_normal_t) == 1 && (ms_qsurf_normal_t)-1 < 0 &&
           sizeof(ms_qsurf_color_t) == 1 && (ms_qsurf_color_t)-1 > 0;
}

ms_qsurf_cl *ms_qsurf_cl_acquire(int any_type, int *absent, ms_error *err)
{
    *absent = 1;
    if (!mesh_types_ok()) {
        ms_error_set(err, "OpenCL writes float positions and 8-bit normals and colours, not "
                          "this build's mesh types");
        return NULL;
    }
    pthread_mutex_lock(&engine_lock);
    ms_error e = {{0}};
    if (engine_state == 0) engine_state = pick_device(&engine, &e) == 0 ? 1 : -1;
    int wanted = any_type || engine.dev.named ||
                 (engine.dev.type & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR));
    if (engine_state == 1 && wanted) engine_state = start(&engine, &e) == 0 ? 2 : -1;
    if (e.msg[0]) snprintf(engine_failure, sizeof engine_failure, "%s", e.msg);
    if (engine_state < 0) {
        *absent = engine_absent;
        ms_error_set(err, "%s", engine_failure);
    } else if (!wanted) {
        ms_error_set(err, "the OpenCL device %s is a CPU", engine.dev.name);
    } else {
        *absent = 0;
        return &engine;
    }
    pthread_mutex_unlock(&engine_lock);
    return NULL;
}

void ms_qsurf_cl_free_mem(cl_mem *m)
{
    if (*m) clReleaseMemObject(*m);
    *m = NULL;
}

static void free_buffers(ms_qsurf_cl *cl)
{
    cl_mem *all[] = {&cl->atoms, &cl->colors, &cl->cells, &cl->ntri, &cl->tri, &cl->edge_from,
                     &cl->dens, &cl->rgb[0], &cl->rgb[1], &cl->rgb[2], &cl->vbase,
                     &cl->pos, &cl->normal, &cl->color, &cl->index};
    for (size_t i = 0; i < MS_COUNTOF(all); i++) ms_qsurf_cl_free_mem(all[i]);
    for (int l = 0; l < MS_QSURF_CL_LEVELS; l++) ms_qsurf_cl_free_mem(&cl->level[l]);
    cl->vcap = cl->tcap = 0;
}

void ms_qsurf_cl_release(ms_qsurf_cl *cl)
{
    free_buffers(cl);
    pthread_mutex_unlock(&engine_lock);
}

const char *ms_qsurf_cl_device_name(const ms_qsurf_cl *cl)
{
    return cl->dev.name;
}

/* Device bytes per grid point of a slab's plane: density (and colour), first vertices,
 * counts (8 bytes per four points), and room for the mesh at 0.1 vertex per point (19
 * bytes a vertex, two triangles of 12). */
#define MESH_PER_POINT 4.3

/* Device bytes: the atom table and cells once, then the slab's planes; three quarters of
 * the device memory at most, no buffer above the allocation limit. */
int ms_qsurf_cl_max_layers(ms_qsurf_cl *cl, const ms_qsurf_grid *g, int colored)
{
    int nc[3];
    ms_qsurf_atomgrid_cells(g, nc);
    double cells = (double)nc[0] * nc[1] * nc[2] + 1;
    double fixed = (double)g->natoms * (colored ? 32 : 16) + cells * 4 + 8192;
    double plane = (double)g->n[0] * g->n[1], dens = plane * (colored ? 16 : 4);
    double perlayer = dens + plane * (4 + 2 + MESH_PER_POINT);
    double room = (double)cl->dev.globalmem * 0.75 - fixed - 3 * dens;
    double layers = MS_MIN(room / perlayer, (double)cl->dev.maxalloc / (4 * plane) - 3);
    if (fixed > (double)cl->dev.maxalloc || !(layers >= 1.0)) return 0;
    return layers > (double)(1 << 30) ? 1 << 30 : (int)layers;
}

cl_mem ms_qsurf_cl_buffer(ms_qsurf_cl *cl, cl_mem_flags flags, size_t bytes, const void *host,
                          cl_int *e)
{
    if (*e != CL_SUCCESS) return NULL;
    if (bytes > cl->dev.maxalloc) {
        *e = CL_INVALID_BUFFER_SIZE;
        return NULL;
    }
    return clCreateBuffer(cl->ctx, flags | (host ? CL_MEM_COPY_HOST_PTR : 0), bytes ? bytes : 16,
                          (void *)host, e);
}

/* The prefix sum's levels for up to n counts: the counts, then the totals of each group
 * of the level below, up to a level of one. */
static void make_levels(ms_qsurf_cl *cl, size_t n, cl_int *e)
{
    size_t per = 4 * cl->scan_local;
    cl->level[0] = ms_qsurf_cl_buffer(cl, CL_MEM_READ_WRITE, n * 8, NULL, e);
    for (int l = 1; l < MS_QSURF_CL_LEVELS; l++) {
        n = (n + per - 1) / per;
        cl->level[l] = ms_qsurf_cl_buffer(cl, CL_MEM_READ_WRITE, n * 8, NULL, e);
        if (n == 1) return;
    }
    if (*e == CL_SUCCESS) *e = CL_INVALID_BUFFER_SIZE;
}

static void upload_tables(ms_qsurf_cl *cl, cl_int *e)
{
    const ms_qsurf_mctab *tab = ms_qsurf_mc_table();
    cl->ntri = ms_qsurf_cl_buffer(cl, CL_MEM_READ_ONLY, sizeof tab->ntri, tab->ntri, e);
    cl->tri = ms_qsurf_cl_buffer(cl, CL_MEM_READ_ONLY, sizeof tab->tri, tab->tri, e);
    cl->edge_from = ms_qsurf_cl_buffer(cl, CL_MEM_READ_ONLY, sizeof ms_qsurf_mc_edge_from,
                                       ms_qsurf_mc_edge_from, e);
}

int ms_qsurf_cl_upload(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, int nx, int ny,
                       int layers, ms_error *err)
{
    cl_int e = CL_SUCCESS;
    size_t ncells = (size_t)ag->nc[0] * ag->nc[1] * ag->nc[2], plane = (size_t)nx * ny;
    size_t slab = plane * (size_t)(layers + 3) * sizeof(float);
    free_buffers(cl);
    cl->nx = nx, cl->ny = ny, cl->planes = layers + 3, cl->colored = ag->rgb != NULL;
    cl->held_zb = 0, cl->held_ze = -1;
    cl->atoms = ms_qsurf_cl_buffer(cl, CL_MEM_READ_ONLY, ag->n * 16, ag->xyzw, &e);
    cl->colors = ms_qsurf_cl_buffer(cl, CL_MEM_READ_ONLY, ag->rgb ? ag->n * 16 : 16, ag->rgb, &e);
    cl->cells = ms_qsurf_cl_buffer(cl, CL_MEM_READ_ONLY, (ncells + 1) * 4, ag->cellstart, &e);
    upload_tables(cl, &e);
    cl->dens = ms_qsurf_cl_buffer(cl, CL_MEM_READ_WRITE, slab, NULL, &e);
    for (int k = 0; k < 3; k++)
        cl->rgb[k] = ms_qsurf_cl_buffer(cl, CL_MEM_READ_WRITE, ag->rgb ? slab : 16, NULL, &e);
    cl->vbase = ms_qsurf_cl_buffer(cl, CL_MEM_READ_WRITE, plane * (size_t)(layers + 1) * 4, NULL,
                                   &e);
    make_levels(cl, (size_t)ms_qsurf_cl_items(nx) * ny * (size_t)(layers + 1), &e);
    if (e != CL_SUCCESS) {
        free_buffers(cl);
        return ms_cl_fail(err, "allocating the device buffers", e);
    }
    return 0;
}

#else /* no OpenCL at build time */

ms_qsurf_cl *ms_qsurf_cl_acquire(int any_type, int *absent, ms_error *err)
{
    *absent = 1;
    ms_error_set(err, "molscope was built without OpenCL");
    return NULL;
}

void ms_qsurf_cl_release(ms_qsurf_cl *cl) {}

int ms_qsurf_cl_max_layers(ms_qsurf_cl *cl, const ms_qsurf_grid *g, int colored)
{
    return 0;
}

int ms_qsurf_cl_upload(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, int nx, int ny,
                       int layers, ms_error *err)
{
    ms_error_set(err, "molscope was built without OpenCL");
    return -1;
}

const char *ms_qsurf_cl_device_name(const ms_qsurf_cl *cl)
{
    return "";
}

#endif
