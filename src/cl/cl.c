/* cl.c: the OpenCL helpers QuickSurf and the OpenCL tracer share (cl.h): error names, the
 * device choice, the cache folders and the program build with its binary cache. */
#include "config.h"
#include "cl/cl.h"
#include "base/safewrite.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

const char *ms_cl_error_name(cl_int e)
{
    switch (e) {
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_BINARY: return "CL_INVALID_BINARY";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case -1001: return "no OpenCL platform (CL_PLATFORM_NOT_FOUND_KHR)";
    default: return "error";
    }
}

int ms_cl_fail(ms_error *err, const char *what, cl_int e)
{
    ms_error_set(err, "OpenCL: %s failed (%d %s)", what, (int)e, ms_cl_error_name(e));
    return -1;
}

/* ---------------------------------------------------------------- the device */

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

int ms_cl_pick_device(ms_cl_device *d, cl_int *rc, const char **want_out)
{
    cl_platform_id plats[16];
    cl_uint np = 0;
    memset(d, 0, sizeof *d);
    *rc = clGetPlatformIDs(16, plats, &np);
    if (*rc != CL_SUCCESS || np == 0) return MS_CL_NOPLATFORM;
    const char *want = getenv("MOLSCOPE_OPENCL_DEVICE");
    int index = 0, best = 99, named = want && *want;
    int by_index = named && isdigit((unsigned char)*want);
    for (cl_uint p = 0; p < np && p < 16; p++) {
        cl_device_id devs[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 16, devs, &nd) != CL_SUCCESS) continue;
        for (cl_uint k = 0; k < nd && k < 16; k++, index++) {
            char name[256] = "";
            cl_device_type t = 0;
            clGetDeviceInfo(devs[k], CL_DEVICE_NAME, sizeof name, name, NULL);
            clGetDeviceInfo(devs[k], CL_DEVICE_TYPE, sizeof t, &t, NULL);
            int take = named ? (by_index ? index == atoi(want) : name_matches(name, want))
                             : device_rank(t) < best;
            if (!take || (named && d->id)) continue;
            d->id = devs[k], d->type = t, d->named = named;
            best = device_rank(t);
            snprintf(d->name, sizeof d->name, "%s", name);
        }
    }
    if (!d->id) {
        *want_out = named ? want : NULL;
        return MS_CL_NODEVICE;
    }
    clGetDeviceInfo(d->id, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof d->globalmem, &d->globalmem, NULL);
    clGetDeviceInfo(d->id, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof d->maxalloc, &d->maxalloc, NULL);
    return 0;
}

/* ---------------------------------------------------------------- the cache folders */

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

int ms_cl_cache_dir(char *dir, size_t size, int own)
{
    const char *mine = own ? getenv("MOLSCOPE_OPENCL_CACHE") : NULL;
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (mine && *mine) snprintf(dir, size, "%s", mine);
    else if (xdg && *xdg) snprintf(dir, size, "%s/molscope", xdg);
    else if (home && *home) snprintf(dir, size, "%s/.cache/molscope", home);
    else return -1;
    return make_dirs(dir);
}

void ms_cl_pocl_cache(const char *dir)
{
    char p[1100];
    if (getenv("POCL_CACHE_DIR")) return;
    snprintf(p, sizeof p, "%s/pocl", dir);
    if (make_dirs(p) == 0) setenv("POCL_CACHE_DIR", p, 0);
}

/* ---------------------------------------------------------------- the program and its cache */

static uint64_t fnv(uint64_t h, const char *s)
{
    for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

/* The cache file of the program on this device. */
static int cache_file(cl_device_id dev, const char *tag, const char *options, const char *source,
                      char *path, size_t size)
{
    char dir[1024], name[256] = "", driver[256] = "", version[256] = "";
    if (ms_cl_cache_dir(dir, sizeof dir, 1)) return -1;
    clGetDeviceInfo(dev, CL_DEVICE_NAME, sizeof name, name, NULL);
    clGetDeviceInfo(dev, CL_DRIVER_VERSION, sizeof driver, driver, NULL);
    clGetDeviceInfo(dev, CL_DEVICE_VERSION, sizeof version, version, NULL);
    uint64_t h = fnv(fnv(fnv(fnv(fnv(14695981039346656037ull, name), driver), version), options),
                     source);
    snprintf(path, size, "%s/%s-%016llx.bin", dir, tag, (unsigned long long)h);
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

/* Keep the program's binary (through base/safewrite: the cache file is replaced whole or
 * not at all). The cache is a convenience: a failure is silent. */
static void save_binary(cl_program prog, const char *path)
{
    size_t n = 0;
    if (clGetProgramInfo(prog, CL_PROGRAM_BINARY_SIZES, sizeof n, &n, NULL) != CL_SUCCESS || !n)
        return;
    unsigned char *bin = malloc(n);
    if (bin && clGetProgramInfo(prog, CL_PROGRAM_BINARIES, sizeof bin, &bin, NULL) == CL_SUCCESS) {
        ms_ofile *out = ms_ofile_open(path, NULL);
        if (out) ms_ofile_finish(out, ms_ofile_write(out, bin, n, NULL) == 0, NULL);
    }
    free(bin);
}

/* The cached binary built, or NULL when there is none or it does not load. */
static cl_program from_cache(cl_context ctx, cl_device_id dev, const char *options,
                             const char *path)
{
    size_t n = 0;
    unsigned char *bin = read_file(path, &n);
    if (!bin) return NULL;
    const unsigned char *b = bin;
    cl_int st, rc;
    cl_program prog = clCreateProgramWithBinary(ctx, 1, &dev, &n, &b, &st, &rc);
    free(bin);
    if (rc == CL_SUCCESS && clBuildProgram(prog, 1, &dev, options, NULL, NULL) == CL_SUCCESS)
        return prog;
    if (prog) clReleaseProgram(prog);
    return NULL;
}

int ms_cl_build(cl_context ctx, cl_device_id dev, const char *source, const char *options,
                const char *cache_tag, cl_program *prog, char *log, size_t logsize,
                ms_error *err)
{
    char path[1200];
    int cached = cache_tag && cache_file(dev, cache_tag, options, source, path, sizeof path) == 0;
    if (cached && (*prog = from_cache(ctx, dev, options, path))) return 0;
    cl_int rc;
    *prog = clCreateProgramWithSource(ctx, 1, &source, NULL, &rc);
    if (rc != CL_SUCCESS) {
        *prog = NULL;
        return ms_cl_fail(err, "clCreateProgramWithSource", rc);
    }
    if (clBuildProgram(*prog, 1, &dev, options, NULL, NULL) != CL_SUCCESS) {
        log[0] = '\0';
        clGetProgramBuildInfo(*prog, dev, CL_PROGRAM_BUILD_LOG, logsize - 1, log, NULL);
        log[logsize - 1] = '\0';
        clReleaseProgram(*prog);
        *prog = NULL;
        return MS_CL_EBUILD;
    }
    if (cached) save_binary(*prog, path);
    return 0;
}
