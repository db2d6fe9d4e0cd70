/* opencl.c: the OpenCL path of QuickSurf's density. One engine per process: the device
 * (a GPU first, or the one MOLSCOPE_OPENCL_DEVICE names by index or name), its context
 * and queue, and the kernel program built once (PoCL keeps compiled kernels in
 * POCL_CACHE_DIR, set here to a per-user cache when unset). The kernel sums the atoms of
 * the cells around each 8x8x8 block of voxels, each work-item computing four planes, with
 * the CPU loops' arithmetic (same exp2 polynomial and per-axis factors, same fused
 * multiply-adds, same atom order), so its slabs agree with the CPU's bit for bit; marching
 * cubes runs on the host. Every error is returned as a message; the caller falls back to
 * the CPU. Without OpenCL at build time these report its absence. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ms_qsurf_cl_fail_after = -1;

#ifdef MS_HAVE_OPENCL
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <ctype.h>
#include <errno.h>
#include <strings.h>
#include <pthread.h>
#include <sys/stat.h>

#define STR_(x) #x
#define STR(x) STR_(x)

static const char *kernel_source =
    "#pragma OPENCL FP_CONTRACT OFF\n"
    "static float qs_exp2(float e)\n"
    "{\n"
    "    float fl = floor(e), f = e - fl;\n"
    "    float p = fma(fma(fma(fma(" STR(MS_QSURF_EXP2_C4) ", f, " STR(MS_QSURF_EXP2_C3) "), f,\n"
    "        " STR(MS_QSURF_EXP2_C2) "), f, " STR(MS_QSURF_EXP2_C1) "), f,\n"
    "        " STR(MS_QSURF_EXP2_C0) ");\n"
    "    return as_float(as_int(p) + (int)fl * 8388608);\n"
    "}\n"
    "static float qs_factor(float w, float d)\n"
    "{\n"
    "    return qs_exp2(max(w * (d * d), -126.0f));\n"
    "}\n"
    "static int qs_cell(float v, float w, int n)\n"
    "{\n"
    "    int c = (int)(v / w);\n"
    "    return c < 0 ? 0 : c >= n ? n - 1 : c;\n"
    "}\n"
    "__kernel __attribute__((reqd_work_group_size(8, 8, 2)))\n"
    "void qs_density(__global const float4 *atoms, __global const float4 *colors,\n"
    "                __global const uint *cellstart, int4 nc, float4 cw, float cut, float elim,\n"
    "                int nx, int ny, int zb, int ze, int colored, __global float *dens,\n"
    "                __global float *red, __global float *green, __global float *blue)\n"
    "{\n"
    "    int x = get_global_id(0), y = get_global_id(1);\n"
    "    int bx = get_group_id(0) * 8, by = get_group_id(1) * 8, bz = zb + get_group_id(2) * 8;\n"
    "    int z = bz + get_local_id(2) * 4;\n"
    "    int cx0 = qs_cell(bx - cut, cw.x, nc.x), cx1 = qs_cell(bx + 7 + cut, cw.x, nc.x);\n"
    "    int cy0 = qs_cell(by - cut, cw.y, nc.y), cy1 = qs_cell(by + 7 + cut, cw.y, nc.y);\n"
    "    int cz0 = qs_cell(bz - cut, cw.z, nc.z), cz1 = qs_cell(bz + 7 + cut, cw.z, nc.z);\n"
    "    float d[4] = {0, 0, 0, 0}, r[4] = {0, 0, 0, 0};\n"
    "    float g[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0};\n"
    "    for (int cz = cz0; cz <= cz1; cz++)\n"
    "        for (int cy = cy0; cy <= cy1; cy++) {\n"
    "            int row = (cz * nc.y + cy) * nc.x;\n"
    "            uint end = cellstart[row + cx1 + 1];\n"
    "            for (uint i = cellstart[row + cx0]; i < end; i++) {\n"
    "                float4 a = atoms[i];\n"
    "                float dx = (float)x - a.x, dy = (float)y - a.y;\n"
    "                float ex = qs_factor(a.w, dx), ey = qs_factor(a.w, dy);\n"
    "                float4 c = colored ? colors[i] : (float4)(0.0f);\n"
    "                for (int k = 0; k < 4; k++) {\n"
    "                    float dz = (float)(z + k) - a.z;\n"
    "                    float e = a.w * fma(dx, dx, fma(dy, dy, dz * dz));\n"
    "                    if (e < elim) continue;\n"
    "                    float v = ex * (ey * qs_factor(a.w, dz));\n"
    "                    d[k] += v;\n"
    "                    r[k] = fma(v, c.x, r[k]), g[k] = fma(v, c.y, g[k]);\n"
    "                    b[k] = fma(v, c.z, b[k]);\n"
    "                }\n"
    "            }\n"
    "        }\n"
    "    if (x >= nx || y >= ny) return;\n"
    "    for (int k = 0; k < 4 && z + k <= ze; k++) {\n"
    "        size_t o = ((size_t)(z + k - zb) * ny + y) * nx + x;\n"
    "        dens[o] = d[k];\n"
    "        if (colored) red[o] = r[k], green[o] = g[k], blue[o] = b[k];\n"
    "    }\n"
    "}\n";

struct ms_qsurf_cl {
    cl_device_id device;
    cl_device_type type;
    cl_context ctx;
    cl_command_queue queue;
    cl_program program;
    cl_kernel kernel;
    cl_ulong globalmem, maxalloc;
    int named;               /* chosen by MOLSCOPE_OPENCL_DEVICE */
    char name[256];
    /* Buffers of the surface being computed. */
    cl_mem atoms, colors, cells, dens, rgb[3];
};

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

static int cl_fail(ms_error *err, const char *what, cl_int e)
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
        return cl_fail(err, "clGetPlatformIDs (no OpenCL platform)", e);
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
    if (e != CL_SUCCESS) return cl_fail(err, "clCreateProgramWithSource", e);
    e = clBuildProgram(cl->program, 1, &cl->device, "", NULL, NULL);
    if (e != CL_SUCCESS) {
        char log[400] = "";
        clGetProgramBuildInfo(cl->program, cl->device, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log,
                              NULL);
        ms_error_set(err, "OpenCL: the density kernel does not build on %s: %s", cl->name, log);
        return -1;
    }
    cl->kernel = clCreateKernel(cl->program, "qs_density", &e);
    if (e != CL_SUCCESS) return cl_fail(err, "clCreateKernel", e);
    return 0;
}

/* The context, queue and kernel, made the first time the device is used. */
static int start(ms_qsurf_cl *cl, ms_error *err)
{
    cl_int e;
    cl->ctx = clCreateContext(NULL, 1, &cl->device, NULL, NULL, &e);
    if (e != CL_SUCCESS) return cl_fail(err, "clCreateContext", e);
    cl->queue = clCreateCommandQueue(cl->ctx, cl->device, 0, &e);
    if (e != CL_SUCCESS) return cl_fail(err, "clCreateCommandQueue", e);
    return build_program(cl, err);
}

ms_qsurf_cl *ms_qsurf_cl_acquire(int any_type, int *absent, ms_error *err)
{
    *absent = 1;
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

static void free_buffers(ms_qsurf_cl *cl)
{
    cl_mem *all[] = {&cl->atoms, &cl->colors, &cl->cells, &cl->dens,
                     &cl->rgb[0], &cl->rgb[1], &cl->rgb[2]};
    for (size_t i = 0; i < MS_COUNTOF(all); i++)
        if (*all[i]) {
            clReleaseMemObject(*all[i]);
            *all[i] = NULL;
        }
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

/* Device bytes: the atom table and cells once, then 4 (or 16) bytes per voxel of a slab;
 * three quarters of the device memory at most, no buffer above the allocation limit. */
int ms_qsurf_cl_max_layers(ms_qsurf_cl *cl, const ms_qsurf_grid *g, int colored)
{
    int nc[3];
    ms_qsurf_atomgrid_cells(g, nc);
    double cells = (double)nc[0] * nc[1] * nc[2] + 1;
    double fixed = (double)g->natoms * (colored ? 32 : 16) + cells * 4;
    double plane = (double)g->n[0] * g->n[1] * sizeof(float);
    double room = (double)cl->globalmem * 0.75 - fixed;
    double planes = MS_MIN(room / (plane * (colored ? 4 : 1)), (double)cl->maxalloc / plane);
    if (fixed > (double)cl->maxalloc || planes < 4.0) return 0;
    return planes - 3.0 > (double)(1 << 30) ? 1 << 30 : (int)(planes - 3.0);
}

static cl_mem buffer(ms_qsurf_cl *cl, cl_mem_flags flags, size_t bytes, void *host, cl_int *e)
{
    if (*e != CL_SUCCESS) return NULL;
    return clCreateBuffer(cl->ctx, flags | (host ? CL_MEM_COPY_HOST_PTR : 0), bytes ? bytes : 16,
                          host, e);
}

int ms_qsurf_cl_upload(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, int nx, int ny,
                       int maxplanes, ms_error *err)
{
    cl_int e = CL_SUCCESS;
    size_t ncells = (size_t)ag->nc[0] * ag->nc[1] * ag->nc[2];
    size_t slab = (size_t)nx * ny * (size_t)maxplanes * sizeof(float);
    free_buffers(cl);
    cl->atoms = buffer(cl, CL_MEM_READ_ONLY, ag->n * 16, ag->xyzw, &e);
    cl->colors = buffer(cl, CL_MEM_READ_ONLY, ag->rgb ? ag->n * 16 : 16, ag->rgb, &e);
    cl->cells = buffer(cl, CL_MEM_READ_ONLY, (ncells + 1) * 4, ag->cellstart, &e);
    cl->dens = buffer(cl, CL_MEM_WRITE_ONLY, slab, NULL, &e);
    for (int k = 0; k < 3; k++)
        cl->rgb[k] = buffer(cl, CL_MEM_WRITE_ONLY, ag->rgb ? slab : 16, NULL, &e);
    if (e != CL_SUCCESS) {
        free_buffers(cl);
        return cl_fail(err, "allocating the device buffers", e);
    }
    return 0;
}

static cl_int set_args(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, const ms_qsurf_slab *s)
{
    cl_int4 nc = {{ag->nc[0], ag->nc[1], ag->nc[2], 0}};
    cl_float4 cw = {{ag->cw[0], ag->cw[1], ag->cw[2], 0.0f}};
    cl_int colored = ag->rgb != NULL;
    cl_int e = 0;
    int a = 0;
    e |= clSetKernelArg(cl->kernel, a++, sizeof(cl_mem), &cl->atoms);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(cl_mem), &cl->colors);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(cl_mem), &cl->cells);
    e |= clSetKernelArg(cl->kernel, a++, sizeof nc, &nc);
    e |= clSetKernelArg(cl->kernel, a++, sizeof cw, &cw);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(float), &ag->cutmax);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(float), &ag->elim);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(int), &s->nx);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(int), &s->ny);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(int), &s->cz);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(int), &s->ze);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(cl_int), &colored);
    e |= clSetKernelArg(cl->kernel, a++, sizeof(cl_mem), &cl->dens);
    for (int k = 0; k < 3; k++) e |= clSetKernelArg(cl->kernel, a++, sizeof(cl_mem), &cl->rgb[k]);
    return e ? CL_INVALID_KERNEL_ARGS : CL_SUCCESS;
}

int ms_qsurf_cl_density(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s,
                        ms_error *err)
{
    if (ms_qsurf_cl_fail_after >= 0 && ms_qsurf_cl_fail_after-- == 0)
        return cl_fail(err, "the density kernel (injected fault)", CL_OUT_OF_RESOURCES);
    size_t planes = (size_t)(s->ze - s->cz + 1), bytes = (size_t)s->nx * s->ny * planes * 4;
    size_t off = (size_t)s->nx * s->ny * (size_t)(s->cz - s->zb);
    size_t local[3] = {8, 8, 2};
    size_t global[3] = {((size_t)s->nx + 7) / 8 * 8, ((size_t)s->ny + 7) / 8 * 8,
                        (planes + 7) / 8 * 2};
    cl_int e = set_args(cl, ag, s);
    if (e != CL_SUCCESS) return cl_fail(err, "clSetKernelArg", e);
    e = clEnqueueNDRangeKernel(cl->queue, cl->kernel, 3, NULL, global, local, 0, NULL, NULL);
    if (e != CL_SUCCESS) return cl_fail(err, "clEnqueueNDRangeKernel", e);
    e = clEnqueueReadBuffer(cl->queue, cl->dens, CL_TRUE, 0, bytes, s->dens + off, 0, NULL, NULL);
    for (int k = 0; e == CL_SUCCESS && ag->rgb && k < 3; k++)
        e = clEnqueueReadBuffer(cl->queue, cl->rgb[k], CL_TRUE, 0, bytes, s->rgb[k] + off, 0, NULL,
                                NULL);
    if (e != CL_SUCCESS) return cl_fail(err, "running the density kernel", e);
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
                       int maxplanes, ms_error *err)
{
    ms_error_set(err, "molscope was built without OpenCL");
    return -1;
}

int ms_qsurf_cl_density(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, ms_qsurf_slab *s,
                        ms_error *err)
{
    ms_error_set(err, "molscope was built without OpenCL");
    return -1;
}

const char *ms_qsurf_cl_device_name(const ms_qsurf_cl *cl)
{
    return "";
}

#endif
