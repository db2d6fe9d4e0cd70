/* engine.c: the process's one OpenCL engine (cl.h): the device, chosen once, with the one
 * context and the one in-order queue that QuickSurf and the OpenCL tracer both use. Each
 * step runs once under a lock and its outcome is kept, a failure included, so every later
 * use answers at once and the same way. */
#include "config.h"
#include "cl/cl.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static ms_cl_engine engine;
static int picked;                 /* 0 not yet, else 1 + ms_cl_pick_device's result */
static cl_int pick_rc;
static const char *pick_want;
static int started;                /* 0 not yet, 1 running, -1 failed */
static char start_failure[sizeof(ms_error)];

int ms_cl_engine_device(ms_cl_engine **e, int own_cache, cl_int *rc, const char **want)
{
    pthread_mutex_lock(&lock);
    if (!picked) {
        char dir[1024];
        if (ms_cl_cache_dir(dir, sizeof dir, own_cache) == 0) ms_cl_pocl_cache(dir);   /* before PoCL */
        picked = 1 + ms_cl_pick_device(&engine.dev, &pick_rc, &pick_want);
    }
    int result = picked - 1;
    *rc = pick_rc;
    *want = pick_want;
    *e = result == 0 ? &engine : NULL;
    pthread_mutex_unlock(&lock);
    return result;
}

static int start(ms_cl_engine *e, ms_error *err)
{
    cl_int rc;
    e->ctx = clCreateContext(NULL, 1, &e->dev.id, NULL, NULL, &rc);
    if (rc != CL_SUCCESS) return ms_cl_fail(err, "clCreateContext", rc);
    e->queue = clCreateCommandQueue(e->ctx, e->dev.id, 0, &rc);
    if (rc != CL_SUCCESS) return ms_cl_fail(err, "clCreateCommandQueue", rc);
    return 0;
}

int ms_cl_engine_start(ms_cl_engine *e, ms_error *err)
{
    pthread_mutex_lock(&lock);
    if (!started) {
        ms_error fail = {{0}};
        started = start(e, &fail) == 0 ? 1 : -1;
        if (started < 0) {
            snprintf(start_failure, sizeof start_failure, "%s", fail.msg);
            if (e->queue) clReleaseCommandQueue(e->queue);
            if (e->ctx) clReleaseContext(e->ctx);
            e->queue = NULL;
            e->ctx = NULL;
        }
    }
    int ok = started > 0;
    if (!ok) ms_error_set(err, "%s", start_failure);
    pthread_mutex_unlock(&lock);
    return ok ? 0 : -1;
}
