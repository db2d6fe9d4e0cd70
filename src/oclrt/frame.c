/* frame.c: an OpenCL render. The options are checked as TachyonInternal checks them, the
 * world is flattened and its BVH built (flatten.c, bvh.c), the parameters (the camera and
 * shader rt/shade.c would use) and every array go to the device once; then one launch of
 * orc_pass per sample pass, the sums, random states and ray counts staying on the device,
 * each launch short (one sample per pixel) so no display watchdog ends it. The pass limit
 * and time budget apply as in rt/frame.c; the sums come back at the end (or after each pass
 * for a pass callback) and become the image as TachyonInternal's do. */
#include "config.h"
#include "oclrt/oclrt_impl.h"
#ifdef MS_HAVE_EMBREE
#include "rt/rt_internal.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

enum { B_P, B_LO0, B_HI0, B_LO1, B_HI1, B_CHILD, B_LEAF, B_QA, B_QB, B_QM, B_TRI, B_VXYZ,
       B_VNORM, B_VCOL, B_GMAT0, B_GMAT1, B_GFLAG, B_ITEM, B_ACCUM, B_RNG, B_RAYS, B_COUNT };

typedef struct ocl_frame {
    orc_engine *e;
    cl_mem buf[B_COUNT];
    size_t npix, global;
    float *accum;               /* host copy of the sums */
} ocl_frame;

/* ---------------------------------------------------------------- parameters */

static void put3(float *P, int at, const float v[3])
{
    P[at] = v[0], P[at + 1] = v[1], P[at + 2] = v[2];
}

/* rt/shade.c's shader of the scene, as params.h lays it out. */
static void make_params(const ms_scene *s, const ms_rt_options *o, const orc_world *w, float *P)
{
    rt_shader sh;
    rt_shader_init(&sh, s, NULL, o->aosamples);
    memset(P, 0, P_COUNT * sizeof(float));
    const rt_camera *c = &sh.cam;
    P[P_WIDTH] = (float)c->width, P[P_HEIGHT] = (float)c->height;
    P[P_ORTHO] = (float)c->ortho, P[P_DOF] = (float)c->dof;
    P[P_FOCAL] = c->focal, P[P_LENS_RADIUS] = c->lens_radius;
    P[P_HALF_W] = c->half_w, P[P_HALF_H] = c->half_h;
    put3(P, P_EYE, c->eye), put3(P, P_DIR, c->dir), put3(P, P_UP, c->up), put3(P, P_RIGHT, c->right);
    P[P_NLIGHTS] = (float)sh.nlights;
    for (int i = 0; i < sh.nlights; i++) {
        put3(P, P_LDIR + 3 * i, sh.ldir[i]);
        put3(P, P_LCOL + 3 * i, sh.lcol[i]);
    }
    P[P_LIGHT_SCALE] = sh.light_scale, P[P_FULL] = (float)sh.full;
    P[P_AO_SAMPLES] = (float)sh.ao_samples;
    put3(P, P_AO_COL, sh.ao_col);
    P[P_BG_MODE] = (float)sh.bg_mode;
    put3(P, P_BG, sh.bg), put3(P, P_BG_TOP, sh.bg_top), put3(P, P_BG_BOT, sh.bg_bot);
    P[P_GRAD_TOP] = sh.grad_top, P[P_GRAD_BOT] = sh.grad_bot;
    P[P_FOG] = (float)sh.fog, P[P_CUEMODE] = (float)sh.cuemode;
    P[P_FOG_START] = sh.fog_start, P[P_FOG_END] = sh.fog_end, P[P_FOG_DENSITY] = sh.fog_density;
    P[P_EPS] = w->eps;
    P[P_DEPTH] = (float)(o->max_depth > 0 && o->max_depth < MS_RT_MAX_DEPTH ? o->max_depth : MS_RT_MAX_DEPTH);
    P[P_NNODES] = (float)w->nnodes;
    P[P_CLIPPED] = (float)w->nclipped;
}

/* ---------------------------------------------------------------- buffers */

static cl_mem buffer(ocl_frame *f, cl_mem_flags flags, size_t bytes, const void *host, cl_int *rc)
{
    if (*rc != CL_SUCCESS) return NULL;
    if (ms_oclrt_fail == MS_OCLRT_FAIL_ALLOC || bytes > f->e->dev.maxalloc) {
        *rc = CL_MEM_OBJECT_ALLOCATION_FAILURE;
        return NULL;
    }
    if (!bytes) host = NULL;
    return clCreateBuffer(f->e->ctx, flags | (host ? CL_MEM_COPY_HOST_PTR : 0), bytes ? bytes : 16,
                          (void *)host, rc);
}

static int upload(ocl_frame *f, const orc_world *w, const float *P, ms_error *err)
{
    const cl_mem_flags ro = CL_MEM_READ_ONLY, rw = CL_MEM_READ_WRITE;
    size_t nn = w->nnodes, nq = w->nq, nt = w->ntri, nv = w->nverts, ng = w->ngeoms;
    struct {
        cl_mem_flags flags;
        size_t bytes;
        const void *host;
    } b[B_COUNT] = {
        {ro, P_COUNT * 4, P}, {ro, nn * 16, w->lo0}, {ro, nn * 16, w->hi0}, {ro, nn * 16, w->lo1},
        {ro, nn * 16, w->hi1}, {ro, nn * 16, w->child}, {ro, w->nleaf * 4, w->leaf},
        {ro, nq * 16, w->qa}, {ro, nq * 16, w->qb}, {ro, nq * 16, w->qm}, {ro, nt * 16, w->tri},
        {ro, nv * 16, w->vxyz}, {ro, nv * 4, w->vnorm}, {ro, nv * 4, w->vcol},
        {ro, ng * 16, w->gmat0}, {ro, ng * 16, w->gmat1}, {ro, ng * 16, w->gflag},
        {ro, w->nitems * ORC_ITEM * 16, w->item}, {rw, f->npix * 12, NULL}, {rw, f->npix * 4, NULL},
        {rw, f->npix * 16, NULL}};
    double total = 0;
    for (int i = 0; i < B_COUNT; i++) total += (double)b[i].bytes;
    cl_int rc = total > 0.9 * (double)f->e->dev.globalmem ? CL_MEM_OBJECT_ALLOCATION_FAILURE : CL_SUCCESS;
    for (int i = 0; i < B_COUNT; i++) f->buf[i] = buffer(f, b[i].flags, b[i].bytes, b[i].host, &rc);
    if (rc != CL_SUCCESS) {
        ms_error_set(err, "OpenCL: %.0f MB of scene and image buffers do not fit on %s (%d %s)",
                     total / 1e6, f->e->dev.name, (int)rc,
                     rc == CL_MEM_OBJECT_ALLOCATION_FAILURE ? "CL_MEM_OBJECT_ALLOCATION_FAILURE" :
                     rc == CL_OUT_OF_RESOURCES ? "CL_OUT_OF_RESOURCES" : "error");
        return -1;
    }
    return 0;
}

static void release(ocl_frame *f)
{
    for (int i = 0; i < B_COUNT; i++)
        if (f->buf[i]) clReleaseMemObject(f->buf[i]);
    free(f->accum);
    memset(f->buf, 0, sizeof f->buf);
    f->accum = NULL;
}

/* ---------------------------------------------------------------- passes */

/* CPU seconds of the process so far, all threads (PoCL's included). */
static double cpu_now(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static int launch_init(ocl_frame *f, ms_error *err)
{
    cl_kernel k = f->e->init;
    cl_uint npix = (cl_uint)f->npix;
    cl_int rc = clSetKernelArg(k, 0, sizeof(cl_mem), &f->buf[B_ACCUM]);
    rc |= clSetKernelArg(k, 1, sizeof(cl_mem), &f->buf[B_RNG]);
    rc |= clSetKernelArg(k, 2, sizeof(cl_mem), &f->buf[B_RAYS]);
    rc |= clSetKernelArg(k, 3, sizeof npix, &npix);
    if (rc != CL_SUCCESS) return ms_cl_fail(err, "clSetKernelArg", rc);
    rc = clEnqueueNDRangeKernel(f->e->queue, k, 1, NULL, &f->global, NULL, 0, NULL, NULL);
    return rc == CL_SUCCESS ? 0 : ms_cl_fail(err, "the first launch", rc);
}

static int launch_pass(ocl_frame *f, int pass, ms_error *err)
{
    cl_kernel k = f->e->pass;
    cl_int rc = CL_SUCCESS;
    for (int i = 0; i < B_COUNT; i++) rc |= clSetKernelArg(k, (cl_uint)i, sizeof(cl_mem), &f->buf[i]);
    rc |= clSetKernelArg(k, B_COUNT, sizeof pass, &pass);
    if (rc != CL_SUCCESS) return ms_cl_fail(err, "clSetKernelArg", rc);
    rc = clEnqueueNDRangeKernel(f->e->queue, k, 1, NULL, &f->global, NULL, 0, NULL, NULL);
    if (rc == CL_SUCCESS) rc = clFinish(f->e->queue);
    return rc == CL_SUCCESS ? 0 : ms_cl_fail(err, "a pass", rc);
}

static int read_accum(ocl_frame *f, ms_error *err)
{
    cl_int rc = clEnqueueReadBuffer(f->e->queue, f->buf[B_ACCUM], CL_TRUE, 0, f->npix * 12, f->accum,
                                    0, NULL, NULL);
    return rc == CL_SUCCESS ? 0 : ms_cl_fail(err, "reading the image", rc);
}

static int read_rays(ocl_frame *f, ms_rt_stats *st, ms_error *err)
{
    uint32_t *r = ms_alloc_array(f->npix, 16);
    if (!r) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    cl_int rc = clEnqueueReadBuffer(f->e->queue, f->buf[B_RAYS], CL_TRUE, 0, f->npix * 16, r, 0,
                                    NULL, NULL);
    memset(st->rays, 0, sizeof st->rays);
    for (size_t i = 0; rc == CL_SUCCESS && i < f->npix; i++)
        for (int k = 0; k < MS_RT_NRAYKINDS; k++) st->rays[k] += r[4 * i + k];
    free(r);
    return rc == CL_SUCCESS ? 0 : ms_cl_fail(err, "reading the ray counts", rc);
}

/* rt/frame.c's to_image: the average, clamped and truncated to 8 bits. */
static void to_image(const float *accum, size_t npix, int passes, ms_image *img)
{
    float scale = 255.0f / (float)passes;
    for (size_t i = 0; i < 3 * npix; i++) {
        float v = accum[i] * scale;
        img->rgb[i] = (uint8_t)(!(v > 0.0f) ? 0.0f : v > 255.0f ? 255.0f : v);
    }
}

typedef struct pass_ctl {
    const ms_rt_options *o;
    ms_oclrt_pass_fn cb;
    void *user;
} pass_ctl;

static int run_passes(ocl_frame *f, const pass_ctl *c, ms_image *img, ms_rt_stats *st, ms_error *err)
{
    int total = c->o->aasamples + 1;
    if (c->o->max_passes > 0 && c->o->max_passes < total) total = c->o->max_passes;
    double t0 = ms_now(), c0 = cpu_now();
    if (launch_init(f, err)) return -1;
    for (int pass = 0; pass < total; pass++) {
        if (launch_pass(f, pass, err)) return -1;
        st->passes = pass + 1;
        if (c->o->progress) {
            double el = ms_now() - t0;
            if (read_rays(f, st, err)) return -1;
            fprintf(stderr, "TachyonLOpenCLInternal: pass %d/%d, %.1f s, %.1f Mrays/s\n", st->passes,
                    total, el, el > 0 ? (double)ms_rt_stats_rays(st) / el / 1e6 : 0.0);
        }
        int stop = c->o->time_budget > 0 && ms_now() - t0 >= c->o->time_budget;
        if (c->cb) {
            if (read_accum(f, err)) return -1;
            to_image(f->accum, f->npix, st->passes, img);
            stop |= c->cb(c->user, st->passes, img) != 0;
        }
        if (stop) break;
    }
    st->trace_s = ms_now() - t0;
    st->trace_cpu_s = cpu_now() - c0;
    if (read_accum(f, err) || read_rays(f, st, err)) return -1;
    to_image(f->accum, f->npix, st->passes, img);
    return 0;
}

/* ---------------------------------------------------------------- render */

/* With Embree: TachyonInternal's memory plan (the image's buffers must fit; what is left
 * bounds Embree's BVH build). Without it the host's own allocations report a shortage. */
static int plan_memory(const ms_scene *s, const ms_rt_options *o, ms_error *err)
{
#ifdef MS_HAVE_EMBREE
    return rt_plan_memory(s, o, err);
#else
    return 0;
#endif
}

static void budget_off(void)
{
#ifdef MS_HAVE_EMBREE
    rt_device_set_budget(0);
#endif
}

static int trace(orc_engine *e, const ms_scene *s, const pass_ctl *c, const orc_world *w,
                 ms_image *img, ms_rt_stats *st, ms_error *err)
{
    ocl_frame f;
    memset(&f, 0, sizeof f);
    f.e = e;
    f.npix = (size_t)s->width * (size_t)s->height;
    f.global = (f.npix + 63) / 64 * 64;
    float P[P_COUNT];
    make_params(s, c->o, w, P);
    f.accum = ms_alloc_array(3 * f.npix, sizeof(float));
    if (!f.accum || ms_image_alloc(img, s->width, s->height, err)) {
        if (!f.accum) ms_error_set(err, "out of memory for a %dx%d image", s->width, s->height);
        release(&f);
        return MS_OCLRT_EINPUT;
    }
    double t0 = ms_now(), c0 = cpu_now();
    int rc = upload(&f, w, P, err);
    st->build_s += ms_now() - t0;         /* the build includes the upload */
    st->build_cpu_s += cpu_now() - c0;
    rc = rc || run_passes(&f, c, img, st, err) ? MS_OCLRT_EDEVICE : 0;
    release(&f);
    return rc;
}

int ms_oclrt_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                    ms_oclrt_pass_fn cb, void *user, ms_error *err)
{
    ms_rt_stats local;
    if (!st) st = &local;
    memset(st, 0, sizeof *st);
    memset(img, 0, sizeof *img);
    if (rt_check_options(s, o, err) || plan_memory(s, o, err)) return MS_OCLRT_EINPUT;
    orc_engine *e = orc_engine_acquire(err);
    if (!e) {
        budget_off();
        return MS_OCLRT_EDEVICE;
    }
    orc_world w;
    double t0 = ms_now(), c0 = cpu_now();
    int rc = orc_world_build(&w, s, err);
    if (rc == 0 && orc_bvh_build(&w, err)) {
        orc_world_free(&w);
        rc = MS_OCLRT_EINPUT;
    }
    st->build_s = ms_now() - t0;
    st->build_cpu_s = cpu_now() - c0;
    if (rc == 0) {
        pass_ctl c = {o, cb, user};
        rc = trace(e, s, &c, &w, img, st, err);
        orc_world_free(&w);
    }
    orc_engine_release(e);
    budget_off();
    if (rc) ms_image_free(img);
    return rc ? (rc == MS_OCLRT_EDEVICE ? MS_OCLRT_EDEVICE : MS_OCLRT_EINPUT) : 0;
}
