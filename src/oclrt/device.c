/* device.c: the OpenCL tracer's engine, one per process: the kernels of kernels.cl on the
 * process's one OpenCL device, context and queue, which QuickSurf shares (cl/cl.h: the device
 * by MOLSCOPE_OPENCL_DEVICE, by index or part of its name, else the first GPU, else any
 * device; MOLSCOPE_NOOPENCL turns OpenCL off). Built programs are
 * cached as binaries in MOLSCOPE_OPENCL_CACHE (else $XDG_CACHE_HOME/molscope or
 * ~/.cache/molscope), one file per device, driver, options and kernel source (cl/cl.h);
 * PoCL also keeps its own cache (POCL_CACHE_DIR, set beside ours when unset). A failure to
 * start is remembered: later renders fall back at once. */
#include "config.h"
#include "oclrt/oclrt_impl.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

static const char *kernel_source =
#include "src/oclrt/kernels.inc"
    ;

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static orc_engine engine;
static int state;               /* 0 not started, 1 running, -1 failed */
static char failure[sizeof(ms_error)];

/* The shared engine's device (cl/cl.h), in the tracer's words when there is none. */
static int pick_device(ms_cl_engine **cl, ms_error *err)
{
    cl_int rc;
    const char *want = NULL;
    switch (ms_cl_engine_device(cl, 1, &rc, &want)) {
    case 0: return 0;
    case MS_CL_NOPLATFORM:
        ms_error_set(err, "no OpenCL platform (%d %s)", (int)rc,
                     rc == -1001 ? "no OpenCL platform" : ms_cl_error_name(rc));
        return -1;
    default:
        if (want) ms_error_set(err, "no OpenCL device matches MOLSCOPE_OPENCL_DEVICE=%s", want);
        else ms_error_set(err, "no OpenCL device");
        return -1;
    }
}

static const char *build_options = "-cl-denorms-are-zero";

/* The program from the cache when it loads, else from source (and then cached); a failed
 * build's message carries the build log's first line(s). */
static int build_program(orc_engine *e, const char *source, ms_error *err)
{
    char log[300];
    int rc = ms_cl_build(e->ctx, e->dev.id, source, build_options,
                         source == kernel_source ? "oclrt" : NULL, &e->program, log, sizeof log,
                         err);
    if (rc != MS_CL_EBUILD) return rc ? -1 : 0;
    for (char *p = log; *p; p++)
        if (*p == '\n' || *p == '\r') *p = ' ';
    ms_error_set(err, "the kernels do not build on %s: %s", e->dev.name,
                 log[0] ? log : "(no build log)");
    return -1;
}

/* The kernels built from source on the shared engine's context. */
static int start(orc_engine *e, const char *source, ms_error *err)
{
    ms_cl_engine *cl;
    if (pick_device(&cl, err) || ms_cl_engine_start(cl, err)) return -1;
    e->dev = cl->dev;
    e->ctx = cl->ctx;
    e->queue = cl->queue;
    if (build_program(e, source, err)) return -1;
    cl_int rc;
    e->init = clCreateKernel(e->program, "orc_init", &rc);
    if (rc == CL_SUCCESS) e->pass = clCreateKernel(e->program, "orc_pass", &rc);
    return rc == CL_SUCCESS ? 0 : ms_cl_fail(err, "clCreateKernel", rc);
}

/* Release the kernels and the program (the context and queue are the shared engine's). */
static void stop(orc_engine *e)
{
    if (e->init) clReleaseKernel(e->init);
    if (e->pass) clReleaseKernel(e->pass);
    if (e->program) clReleaseProgram(e->program);
    memset(e, 0, sizeof *e);
}

/* An injected build failure: a program that does not compile, on a throwaway engine. */
static void injected_build_failure(ms_error *err)
{
    orc_engine e;
    memset(&e, 0, sizeof e);
    if (start(&e, "__kernel void orc_init(void) { no such thing }", err) == 0)
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
        state = start(&engine, kernel_source, &e) == 0 ? 1 : -1;
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
    return engine.dev.name;
}
