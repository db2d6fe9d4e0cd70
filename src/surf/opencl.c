/* opencl.c: the engine of QuickSurf's OpenCL path. One engine per process: the device
 * (a GPU first, or the one MOLSCOPE_OPENCL_DEVICE names by index or name), its context and
 * queue, and the kernels of kernels.cl built once (PoCL keeps compiled kernels in
 * POCL_CACHE_DIR, set here to a per-user cache when unset); and the buffers of the surface
 * being computed, sized from the device's memory. opencl_slab.c runs the slabs. Every
 * error is returned as a message; the caller falls back to the CPU. Without OpenCL at
 * build time these report its absence. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ms_qsurf_cl_fail_after = -1;
int ms_qsurf_cl_fail_stage = MS_QSURF_CL_FAIL_DENSITY;

#ifdef MS_HAVE_OPENCL
#include "surf/opencl_impl.h"

#include <ctype.h>
#include <errno.h>
#include <strings.h>
#include <pthread.h>
#include <sys/stat.h>

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

static const char *cl_error_name(cl_int e)
{
    switch (e) {
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case -1001: return "no OpenCL platform (CL_PLATFORM_NOT_FOUND_KHR)";
    default: return "error";
    }
}

int ms_qsurf_cl_fail(ms_error *err, const char *what, cl_int e)
{
    ms_error_set(err, "OpenCL: %s failed (%d %s)", what, (int)e, cl_error_name(e));
    return -1;
}

/* PoCL compiles kernels once into its cache: give it a per-user folder unless the user
 * chose one. */
static void pocl_cache_dir(void)
{
    if (getenv("POCL_CACHE_DIR")) return;
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char dir[1024];
    if (xdg && *xdg) snprintf(dir, sizeof dir, "%s/molscope", xdg);
    else if (home && *home) snprintf(dir, sizeof dir, "%s/.cache/molscope", home);
    else return;
    for (char *p = dir + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            mkdir(dir, 0700);
            *p = '/';
        }
    mkdir(dir, 0700);
    size_t len = strlen(dir);
    if (len + 7 >= sizeof dir) return;
    memcpy(dir + len, "/pocl", 6);
    if (mkdir(dir, 0700) == 0 || errno == EEXIST) setenv("POCL_CACHE_DIR", dir, 0);
}

static int name_matches(const char *name, const char *want)
{
    size_t n = strlen(want);
    for (const char *p = name; *p; p++)
        if (strncasecmp(p, want, n) == 0) return 1;
    return 0;
}

/* Rank of a device for automatic choice: GPU, accelerator, then anything. */
static int device_rank(cl_device_type t)
{
    return (t & CL_DEVICE_TYPE_GPU) ? 0 : (t & CL_DEVICE_TYPE_ACCELERATOR) ? 1 : 2;
}

/* Every device of every platform; pick by MOLSCOPE_OPENCL_DEVICE or by rank. */
static int pick_device(ms_qsurf_cl *cl, ms_error *err)
{
    cl_platform_id plats[16];
    cl_uint np = 0;
    cl_int e = clGetPlatformIDs(16, plats, &np);
    if (e != CL_SUCCESS || np == 0) {
        engine_absent = 1;
        return ms_qsurf_cl_fail(err, "clGetPlatformIDs (no OpenCL platform)", e);
    }
    const char *want = getenv("MOLSCOPE_OPENCL_DEVICE");
    int index = 0, best = 99;
    int by_index = want && *want && isdigit((unsigned char)*want);
    for (cl_uint p = 0; p < np && p < 16; p++) {
        cl_device_id devs[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 16, devs, &nd) != CL_SUCCESS) continue;
        for (cl_uint d = 0; d < nd && d < 16; d++, index++) {
            char name[256] = "";
            cl_device_type t = 0;
            clGetDeviceInfo(devs[d], CL_DEVICE_NAME, sizeof name, name, NULL);
            clGetDeviceInfo(devs[d], CL_DEVICE_TYPE, sizeof t, &t, NULL);
            int take = want && *want ? (by_index ? index == atoi(want) : name_matches(name, want))
                                     : device_rank(t) < best;
            if (!take || (want && *want && cl->named)) continue;
            cl->device = devs[d], cl->type = t, cl->named = want && *want;
            best = device_rank(t);
            snprintf(cl->name, sizeof cl->name, "%s", name);
        }
    }
    if (!cl->device) {
        engine_absent = 1;
        ms_error_set(err, want && *want ? "OpenCL: no device matches MOLSCOPE_OPENCL_DEVICE=%s"
                                        : "OpenCL: no device%s", want && *want ? want : "");
        return -1;
    }
    clGetDeviceInfo(cl->device, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof cl->globalmem, &cl->globalmem,
                    NULL);
    clGetDeviceInfo(cl->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof cl->maxalloc, &cl->maxalloc,
                    NULL);
    return 0;
}

static int build_program(ms_qsurf_cl *cl, ms_error *err)
{
    cl_int e;
    cl->program = clCreateProgramWithSource(cl->ctx, 1, &kernel_source, NULL, &e);
    if (e != CL_SUCCESS) return ms_qsurf_cl_fail(err, "clCreateProgramWithSource", e);
    e = clBuildProgram(cl->program, 1, &cl->device, build_options, NULL, NULL);
    if (e != CL_SUCCESS) {
        char log[400] = "";
        clGetProgramBuildInfo(cl->program, cl->device, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log,
                              NULL);
        ms_error_set(err, "OpenCL: the QuickSurf kernels do not build on %s: %s", cl->name, log);
        return -1;
    }
    for (int k = 0; k < K_COUNT_OF; k++) {
        cl->k[k] = clCreateKernel(cl->program, kernel_names[k], &e);
        if (e != CL_SUCCESS) return ms_qsurf_cl_fail(err, "clCreateKernel", e);
    }
    return 0;
}

/* The prefix sum's work-group: a power of two up to 256 that the kernel allows. */
static int scan_group(ms_qsurf_cl *cl, ms_error *err)
{
    size_t most = 0;
    cl_int e = clGetKernelWorkGroupInfo(cl->k[K_SCAN], cl->device, CL_KERNEL_WORK_GROUP_SIZE,
                                        sizeof most, &most, NULL);
    if (e != CL_SUCCESS) return ms_qsurf_cl_fail(err, "clGetKernelWorkGroupInfo", e);
    for (cl->scan_local = 256; cl->scan_local > most; cl->scan_local /= 2) {}
    if (cl->scan_local < 32) {
        ms_error_set(err, "OpenCL: %s runs work-groups of %zu items only", cl->name, most);
        return -1;
    }
    return 0;
}

/* The context, queue and kernels, made the first time the device is used. */
static int start(ms_qsurf_cl *cl, ms_error *err)
{
    cl_int e;
    cl->ctx = clCreateContext(NULL, 1, &cl->device, NULL, NULL, &e);
    if (e != CL_SUCCESS) return ms_qsurf_cl_fail(err, "clCreateContext", e);
    cl->queue = clCreateCommandQueue(cl->ctx, cl->device, 0, &e);
    if (e != CL_SUCCESS) return ms_qsurf_cl_fail(err, "clCreateCommandQueue", e);
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
    if (engine_state == 0) {
        pocl_cache_dir();
        engine_state = pick_device(&engine, &e) == 0 ? 1 : -1;
    }
    int wanted = any_type || engine.named ||
                 (engine.type & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR));
    if (engine_state == 1 && wanted) engine_state = start(&engine, &e) == 0 ? 2 : -1;
    if (e.msg[0]) snprintf(engine_failure, sizeof engine_failure, "%s", e.msg);
    if (engine_state < 0) {
        *absent = engine_absent;
        ms_error_set(err, "%s", engine_failure);
    } else if (!wanted) {
        ms_error_set(err, "the OpenCL device %s is a CPU", engine.name);
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
    return cl->name;
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
    double room = (double)cl->globalmem * 0.75 - fixed - 3 * dens;
    double layers = MS_MIN(room / perlayer, (double)cl->maxalloc / (4 * plane) - 3);
    if (fixed > (double)cl->maxalloc || !(layers >= 1.0)) return 0;
    return layers > (double)(1 << 30) ? 1 << 30 : (int)layers;
}

cl_mem ms_qsurf_cl_buffer(ms_qsurf_cl *cl, cl_mem_flags flags, size_t bytes, const void *host,
                          cl_int *e)
{
    if (*e != CL_SUCCESS) return NULL;
    if (bytes > cl->maxalloc) {
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
        return ms_qsurf_cl_fail(err, "allocating the device buffers", e);
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
