/* tachyon_internal.c: the `TachyonInternal` render device, VMD's name for its built-in
 * Tachyon: `render TachyonInternal frame.tga` ray traces the scene into an image (rt.h) with
 * the device's `render aasamples` and `render aosamples` counts (VMD's defaults, 12 and 12),
 * the pass limit and time budget of MOLSCOPE_RT_PASSES and MOLSCOPE_RT_TIME, and progress
 * lines on a terminal. */
#include "config.h"
#include "render/render.h"
#include "rt/rt.h"

static int write_internal(const ms_scene *s, const char *path, ms_error *err)
{
    ms_rt_options o;
    if (ms_rt_options_for_scene(s, &o, err)) return -1;
    return ms_rt_write(s, &o, path, NULL, err);
}

static int image_internal(const ms_scene *s, ms_image *img, ms_error *err)
{
    ms_rt_options o;
    if (ms_rt_options_for_scene(s, &o, err)) return -1;
    return ms_rt_render(s, &o, img, NULL, err);
}

const ms_render_device ms_render_tachyon_internal = {
    .name = "TachyonInternal",
    .description = "Tachyon-style ray tracer built in (Embree): images .png .tga .ppm .bmp",
    .default_cmd = "display %s",
    .has_aa = 1, .aasamples = 12, .aosamples = 12,
    .write = write_internal,
    .image = image_internal};
