/* cl.h: what molscope's two OpenCL users (QuickSurf's engine, src/surf/opencl.c, and the
 * OpenCL tracer, src/oclrt/device.c) share: OpenCL errors as messages, the choice of the
 * device (MOLSCOPE_OPENCL_DEVICE), the one engine (that device with one context and one
 * queue, engine.c), the per-user cache folder (and PoCL's beside it), and the build of a
 * program kept as a binary in that folder. Only built with OpenCL; the
 * messages are each caller's own, so these return codes where a caller words the failure. */
#ifndef MS_CL_H
#define MS_CL_H

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stddef.h>

#include "base/base.h"

/* An OpenCL error code's name ("error" for the ones not listed). */
const char *ms_cl_error_name(cl_int e);
/* An OpenCL failure as a message: "OpenCL: what failed (code name)"; returns -1. */
int ms_cl_fail(ms_error *err, const char *what, cl_int e);

typedef struct ms_cl_device {
    cl_device_id id;
    cl_device_type type;
    cl_ulong globalmem, maxalloc;
    int named;               /* chosen by MOLSCOPE_OPENCL_DEVICE */
    char name[256];
} ms_cl_device;

enum { MS_CL_NOPLATFORM = -1, MS_CL_NODEVICE = -2, MS_CL_EBUILD = -3 };

/* The device to use over every device of every platform: the one MOLSCOPE_OPENCL_DEVICE
 * names (by index in platform order, or by part of its name, case-insensitively), else the
 * first GPU, else the first accelerator, else the first device. 0; MS_CL_NOPLATFORM with *rc
 * clGetPlatformIDs' code; or MS_CL_NODEVICE (*want: the variable's value, NULL when unset). */
int ms_cl_pick_device(ms_cl_device *d, cl_int *rc, const char **want);

/* ---- the engine: one per process, shared by both users (each builds its own program on
 * its context and keeps its own lock for its kernels and buffers). */
typedef struct ms_cl_engine {
    ms_cl_device dev;
    cl_context ctx;          /* NULL until ms_cl_engine_start */
    cl_command_queue queue;  /* in order */
} ms_cl_engine;

/* The engine's device, chosen the first time (PoCL given its cache beside the cache folder
 * first, own as in ms_cl_cache_dir), the outcome kept: 0 with *e, else what
 * ms_cl_pick_device returned, with *rc and *want as it sets them. */
int ms_cl_engine_device(ms_cl_engine **e, int own_cache, cl_int *rc, const char **want);
/* The engine's context and queue, made the first time: 0, or -1 with err set
 * ("OpenCL: clCreateContext (...)"), the failure kept and repeated. */
int ms_cl_engine_start(ms_cl_engine *e, ms_error *err);

/* The per-user cache folder, made when missing: MOLSCOPE_OPENCL_CACHE when own is set and
 * the variable is, else $XDG_CACHE_HOME/molscope, else ~/.cache/molscope. 0, or -1. */
int ms_cl_cache_dir(char *dir, size_t size, int own);
/* Give PoCL <dir>/pocl as its kernel cache unless POCL_CACHE_DIR is set (call it before
 * PoCL starts). */
void ms_cl_pocl_cache(const char *dir);

/* Build source for the device with options. With a cache tag the program is read from
 * <cache folder>/<tag>-<hash>.bin when that loads (the hash: FNV-1a of the device's name,
 * driver and version, the options and the source), and saved there after a build from
 * source. 0 with *prog; -1 with err set when an OpenCL call fails; MS_CL_EBUILD when the
 * source does not compile, with the start of the build log in log[0..logsize). */
int ms_cl_build(cl_context ctx, cl_device_id dev, const char *source, const char *options,
                const char *cache_tag, cl_program *prog, char *log, size_t logsize,
                ms_error *err);

#endif
