/* device.c: the OpenCL tracer's engine, one per process: the device (MOLSCOPE_OPENCL_DEVICE
 * by index or part of its name, else the first GPU, else any device; MOLSCOPE_NOOPENCL turns
 * OpenCL off), its context and queue, and the kernels of kernels.cl. Built programs are
 * cached as binaries in MOLSCOPE_OPENCL_CACHE (else $XDG_CACHE_HOME/molscope or
 * ~/.cache/molscope), one file per device, driver and kernel source (an FNV-1a hash of all
 * three in the name); PoCL also keeps its own cache (POCL_CACHE_DIR, set beside ours when
 * unset). A failure to start is remembered: later renders fall back at once. */
#include "config.h"
#include "oclrt/oclrt_impl.h"

#include <ctype.h>
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kernel_source =
#include "src/oclrt/kernels.inc"
    ;

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static orc_engine engine;
static int state;               /* 0 not started, 1 running, -1 failed */
static char failure[sizeof(ms_error)];

static const char *cl_error_name(cl_int e)
{
    switch (e) {
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_BINARY: return "CL_INVALID_BINARY";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case -1001: return "no OpenCL platform";
    default: return "error";
    }
}

int orc_fail(ms_error *err, const char *what, cl_int e)
{
    ms_error_set(err, "OpenCL: %s failed (%d %s)", what, (int)e, cl_error_name(e));
    return -1;
}

/* ---------------------------------------------------------------- the cache folder */

/* mkdir -p; 0 when the folder exists after. */
static int make_dirs(char *dir)
{
    for (char *p = dir + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            mkdir(dir, 0700);
            *p = '/';
        }
    return mkdir(dir, 0700) == 0 || errno == EEXIST ? 0 : -1;
}

static int cache_dir(char *dir, size_t size)
{
    const char *own = getenv("MOLSCOPE_OPENCL_CACHE"), *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (own && *own) snprintf(dir, size, "%s", own);
    else if (xdg && *xdg) snprintf(dir, size, "%s/molscope", xdg);
    else if (home && *home) snprintf(dir, size, "%s/.cache/molscope", home);
    else return -1;
    return make_dirs(dir);
}

static void pocl_cache(const char *dir)
{
    char p[1100];
    if (getenv("POCL_CACHE_DIR")) return;
    snprintf(p, sizeof p, "%s/pocl", dir);
    if (make_dirs(p) == 0) setenv("POCL_CACHE_DIR", p, 0);
}

static uint64_t fnv(uint64_t h, const char *s)
{
    for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

/* The cache file of the program on this device. */
static int cache_file(cl_device_id dev, const char *options, char *path, size_t size)
{
    char dir[1024], name[256] = "", driver[256] = "", version[256] = "";
    if (cache_dir(dir, sizeof dir)) return -1;
    clGetDeviceInfo(dev, CL_DEVICE_NAME, sizeof name, name, NULL);
    clGetDeviceInfo(dev, CL_DRIVER_VERSION, sizeof driver, driver, NULL);
    clGetDeviceInfo(dev, CL_DEVICE_VERSION, sizeof version, version, NULL);
    uint64_t h = fnv(fnv(fnv(fnv(fnv(14695981039346656037ull, name), driver), version), options),
                     kernel_source);
    snprintf(path, size, "%s/oclrt-%016llx.bin", dir, (unsigned long long)h);
    return 0;
}

static unsigned char *read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long len = ftell(f);
        if (len > 0 && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)len))) {
            if (fread(buf, 1, (size_t)len, f) == (size_t)len) *n = (size_t)len;
            else free(buf), buf = NULL;
        }
    }
    fclose(f);
    return buf;
}

/* Keep the program's binary (to a temporary name renamed at the end). */
static void save_binary(cl_program prog, const char *path)
{
    size_t n = 0;
    if (clGetProgramInfo(prog, CL_PROGRAM_BINARY_SIZES, sizeof n, &n, NULL) != CL_SUCCESS || !n) return;
    unsigned char *bin = malloc(n);
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%.1200s.%ld.tmp", path, (long)getpid());
    if (bin && clGetProgramInfo(prog, CL_PROGRAM_BINARIES, sizeof bin, &bin, NULL) == CL_SUCCESS) {
        FILE *f = fopen(tmp, "wb");
        int ok = f && fwrite(bin, 1, n, f) == n;
        if (f && fclose(f) != 0) ok = 0;
        if (!ok || rename(tmp, path) != 0) unlink(tmp);
    }
    free(bin);
}

/* ---------------------------------------------------------------- device and program */

static int name_matches(const char *name, const char *want)
{
    size_t n = strlen(want);
    for (const char *p = name; *p; p++)
        if (strncasecmp(p, want, n) == 0) return 1;
    return 0;
}

static int pick_device(orc_engine *e, ms_error *err)
{
    cl_platform_id plats[16];
    cl_uint np = 0;
    cl_int rc = clGetPlatformIDs(16, plats, &np);
    if (rc != CL_SUCCESS || np == 0) {
        ms_error_set(err, "no OpenCL platform (%d %s)", (int)rc, cl_error_name(rc));
        return -1;
    }
    const char *want = getenv("MOLSCOPE_OPENCL_DEVICE");
    int index = 0, best = 99, named = want && *want, by_index = named && isdigit((unsigned char)*want);
    for (cl_uint p = 0; p < np && p < 16; p++) {
        cl_device_id devs[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 16, devs, &nd) != CL_SUCCESS) continue;
        for (cl_uint d = 0; d < nd && d < 16; d++, index++) {
            char name[256] = "";
            cl_device_type t = 0;
            clGetDeviceInfo(devs[d], CL_DEVICE_NAME, sizeof name, name, NULL);
            clGetDeviceInfo(devs[d], CL_DEVICE_TYPE, sizeof t, &t, NULL);
            int rank = (t & CL_DEVICE_TYPE_GPU) ? 0 : (t & CL_DEVICE_TYPE_ACCELERATOR) ? 1 : 2;
            int take = named ? (by_index ? index == atoi(want) : name_matches(name, want)) : rank < best;
            if (!take || (named && e->device)) continue;
            e->device = devs[d];
            best = rank;
            snprintf(e->name, sizeof e->name, "%s", name);
        }
    }
    if (!e->device) {
        if (named) ms_error_set(err, "no OpenCL device matches MOLSCOPE_OPENCL_DEVICE=%s", want);
        else ms_error_set(err, "no OpenCL device");
        return -1;
    }
    clGetDeviceInfo(e->device, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof e->globalmem, &e->globalmem, NULL);
    clGetDeviceInfo(e->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof e->maxalloc, &e->maxalloc, NULL);
    return 0;
}

/* The build log's first line(s), for the fallback message. */
static void build_failed(cl_program prog, cl_device_id dev, const char *name, ms_error *err)
{
    char log[300] = "";
    clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log, NULL);
    for (char *p = log; *p; p++)
        if (*p == '\n' || *p == '\r') *p = ' ';
    ms_error_set(err, "the kernels do not build on %s: %s", name, log[0] ? log : "(no build log)");
}

static const char *build_options = "-cl-denorms-are-zero";

/* The program from the cache when it loads, else from source (and then cached). */
static int build_program(orc_engine *e, const char *source, ms_error *err)
{
    char path[1200];
    int cached = source == kernel_source && cache_file(e->device, build_options, path, sizeof path) == 0;
    size_t n = 0;
    unsigned char *bin = cached ? read_file(path, &n) : NULL;
    cl_int rc;
    if (bin) {
        const unsigned char *b = bin;
        cl_int st;
        e->program = clCreateProgramWithBinary(e->ctx, 1, &e->device, &n, &b, &st, &rc);
        free(bin);
        if (rc == CL_SUCCESS && clBuildProgram(e->program, 1, &e->device, build_options, NULL, NULL) == CL_SUCCESS)
            return 0;
        if (e->program) clReleaseProgram(e->program);
        e->program = NULL;
    }
    e->program = clCreateProgramWithSource(e->ctx, 1, &source, NULL, &rc);
    if (rc != CL_SUCCESS) return orc_fail(err, "clCreateProgramWithSource", rc);
    if (clBuildProgram(e->program, 1, &e->device, build_options, NULL, NULL) != CL_SUCCESS) {
        build_failed(e->program, e->device, e->name, err);
        return -1;
    }
    if (cached) save_binary(e->program, path);
    return 0;
}

static int start(orc_engine *e, const char *source, ms_error *err)
{
    cl_int rc;
    e->ctx = clCreateContext(NULL, 1, &e->device, NULL, NULL, &rc);
    if (rc != CL_SUCCESS) return orc_fail(err, "clCreateContext", rc);
    e->queue = clCreateCommandQueue(e->ctx, e->device, 0, &rc);
    if (rc != CL_SUCCESS) return orc_fail(err, "clCreateCommandQueue", rc);
    if (build_program(e, source, err)) return -1;
    e->init = clCreateKernel(e->program, "orc_init", &rc);
    if (rc == CL_SUCCESS) e->pass = clCreateKernel(e->program, "orc_pass", &rc);
    return rc == CL_SUCCESS ? 0 : orc_fail(err, "clCreateKernel", rc);
}

static void stop(orc_engine *e)
{
    if (e->init) clReleaseKernel(e->init);
    if (e->pass) clReleaseKernel(e->pass);
    if (e->program) clReleaseProgram(e->program);
    if (e->queue) clReleaseCommandQueue(e->queue);
    if (e->ctx) clReleaseContext(e->ctx);
    memset(e, 0, sizeof *e);
}

/* An injected build failure: a program that does not compile, on a throwaway engine. */
static void injected_build_failure(ms_error *err)
{
    orc_engine e;
    memset(&e, 0, sizeof e);
    if (pick_device(&e, err) == 0 && start(&e, "__kernel void orc_init(void) { no such thing }", err) == 0)
        ms_error_set(err, "the injected build failure built");
    stop(&e);
}

orc_engine *orc_engine_acquire(ms_error *err)
{
    if (ms_env_flag("MOLSCOPE_NOOPENCL")) {
        ms_error_set(err, "OpenCL is off (MOLSCOPE_NOOPENCL)");
        return NULL;
    }
    pthread_mutex_lock(&lock);
    if (ms_oclrt_fail == MS_OCLRT_FAIL_BUILD) {
        injected_build_failure(err);
        pthread_mutex_unlock(&lock);
        return NULL;
    }
    if (state == 0) {
        ms_error e = {{0}};
        char dir[1024];
        if (cache_dir(dir, sizeof dir) == 0) pocl_cache(dir);     /* before PoCL starts */
        state = pick_device(&engine, &e) == 0 && start(&engine, kernel_source, &e) == 0 ? 1 : -1;
        if (state < 0) {
            snprintf(failure, sizeof failure, "%s", e.msg);
            stop(&engine);
        }
    }
    if (state > 0) return &engine;
    ms_error_set(err, "%s", failure);
    pthread_mutex_unlock(&lock);
    return NULL;
}

void orc_engine_release(orc_engine *e)
{
    pthread_mutex_unlock(&lock);
}

const char *ms_oclrt_device_name(void)
{
    return engine.name;
}
