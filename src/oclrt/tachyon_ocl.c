/* tachyon_ocl.c: the `TachyonLOpenCLInternal` render device (and `TachyonLOptiXInternal`,
 * VMD's name for its GPU tracer, so that VMD scripts run): oclrt.h's tracer with the
 * device's `render aasamples` and `render aosamples` (VMD's defaults, 12 and 12) and
 * TachyonInternal's pass limit, time budget and progress lines, falling back to
 * TachyonInternal with a one-line message when OpenCL cannot render. Without OpenCL at
 * build time every render falls back. */
#include "config.h"
#include "oclrt/oclrt.h"
#include "render/render.h"

#include <stdio.h>
#include <string.h>

int ms_oclrt_fail = MS_OCLRT_FAIL_NONE;
int ms_oclrt_own_bvh;

#ifndef MS_HAVE_OPENCL
int ms_oclrt_available(void)
{
    return 0;
}

int ms_oclrt_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                    ms_oclrt_pass_fn cb, void *user, ms_error *err)
{
    memset(img, 0, sizeof *img);
    if (st) memset(st, 0, sizeof *st);
    ms_error_set(err, "molscope was built without OpenCL");
    return MS_OCLRT_EDEVICE;
}

const char *ms_oclrt_device_name(void)
{
    return "";
}
#else
int ms_oclrt_available(void)
{
    return 1;
}
#endif

typedef struct ocl_job {
    const ms_scene *s;
    const ms_rt_options *o;
    ms_rt_stats *st;
    int *fell_back;
} ocl_job;

/* The image on OpenCL, else (with a line saying why) on TachyonInternal. */
static int render_job(void *user, ms_image *img, ms_error *err)
{
    ocl_job *j = user;
    int rc = ms_oclrt_render(j->s, j->o, img, j->st, NULL, NULL, err);
    if (rc != MS_OCLRT_EDEVICE) return rc;
    fprintf(stderr, "TachyonLOpenCLInternal: %s; rendering with TachyonInternal\n", err->msg);
    if (j->fell_back) *j->fell_back = 1;
    return ms_rt_render(j->s, j->o, img, j->st, err);
}

int ms_oclrt_write(const ms_scene *s, const ms_rt_options *o, const char *path, ms_rt_stats *st,
                   int *fell_back, ms_error *err)
{
    if (fell_back) *fell_back = 0;
    ocl_job j = {s, o, st, fell_back};
    return ms_render_write_image(path, render_job, &j, err);
}

static int write_ocl(const ms_scene *s, const char *path, ms_error *err)
{
    ms_rt_options o;
    if (ms_rt_options_for_scene(s, &o, err)) return -1;
    return ms_oclrt_write(s, &o, path, NULL, NULL, err);
}

static int image_ocl(const ms_scene *s, ms_image *img, ms_error *err)
{
    ms_rt_options o;
    if (ms_rt_options_for_scene(s, &o, err)) return -1;
    ocl_job j = {s, &o, NULL, NULL};
    return render_job(&j, img, err);
}

const ms_render_device ms_render_tachyon_ocl = {
    .name = "TachyonLOpenCLInternal",
    .description = "Tachyon-style ray tracer built in, on OpenCL (GPU or PoCL): images .png .tga .ppm .bmp",
    .default_cmd = "display %s",
    .has_aa = 1, .aasamples = 12, .aosamples = 12,
    .write = write_ocl,
    .image = image_ocl};

const ms_render_device ms_render_tachyon_optix = {
    .name = "TachyonLOptiXInternal",
    .description = "VMD's name for its GPU ray tracer: molscope's TachyonLOpenCLInternal",
    .default_cmd = "display %s",
    .has_aa = 1, .aasamples = 12, .aosamples = 12,
    .write = write_ocl,
    .image = image_ocl};
