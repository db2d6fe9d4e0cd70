/* frames.c: the images of the live view (live.h): the change check (scene version, scene
 * builds by others, colours, materials, display size), a rasterized image at once when a GL
 * display runs (while the page drags, a coarse one of decimated meshes), then
 * TachyonInternal passes at idle time, each encoded as a PNG that
 * replaces the last; and the view changes the page sends, checked and applied. */
#include "config.h"
#include "live/live.h"
#include "assemble/devices.h"
#include "assemble/view.h"
#include "gl/gl.h"
#include "scene/color.h"
#include "scene/material.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tcl.h>

#define CHECK_MS 100        /* how often a quiet session is checked for changes */
#define INTERACT_S 0.3      /* a drag's images are coarse until the view rests this long */

/* ---------------------------------------------------------------- images */

/* The image as PNG (fast settings) in place of the current one. */
static int publish(ms_live_frames *f, const ms_image *img, int passes, ms_error *err)
{
    unsigned char *buf;
    size_t len;
    if (ms_image_png_mem(img, &buf, &len, err)) return -1;
    free(f->png);
    f->png = buf;
    f->png_len = len;
    f->passes = passes;
    f->serial++;
    if (f->on_image) f->on_image(f->ud);
    return 0;
}

static void drop_scene(ms_live_frames *f)
{
    ms_rt_session_end(f->rt);
    f->rt = NULL;
    f->rt_pending = 0;
    if (f->have_scene) ms_scene_free(&f->scene);
    f->have_scene = 0;
    f->valid = 0;
}

void ms_live_frames_set_raster(ms_live_frames *f, int raster_only)
{
    if (f->raster_only == raster_only) return;
    f->raster_only = raster_only;
    f->valid = 0;                    /* the next step makes the scene and its image again */
    ms_live_frames_kick(f);
}

void ms_live_frames_interact(ms_live_frames *f)
{
    f->interact_until = ms_now() + INTERACT_S;
    ms_live_frames_kick(f);
}

int ms_live_frames_stale(const ms_live_frames *f)
{
    const ms_app *app = f->app;
    return !f->valid || (f->coarse && ms_now() >= f->interact_until) || f->version != app->world.scene_version || f->builds != app->world.scene_builds ||
           (app->world.colors && f->colors_version != app->world.colors->version) ||
           (app->world.materials && f->materials_version != app->world.materials->version) ||
           f->width != app->world.width || f->height != app->world.height;
}

static void remember(ms_live_frames *f)
{
    ms_app *app = f->app;
    f->valid = 1;
    f->version = app->world.scene_version;
    f->builds = app->world.scene_builds;
    f->colors_version = app->world.colors ? app->world.colors->version : 0;
    f->materials_version = app->world.materials ? app->world.materials->version : 0;
    f->width = app->world.width;
    f->height = app->world.height;
}

/* TachyonInternal's sample counts from `render aasamples|aosamples TachyonInternal`. */
static void rt_settings(ms_live_frames *f, ms_rt_options *o)
{
    ms_rt_options_default(o);
    const ms_render_device *dev = ms_render_find("TachyonInternal");
    ms_render_setting *set = dev && f->app->world.renderers ?
                             ms_render_setting_of(f->app->world.renderers, dev) : NULL;
    if (set) {
        o->aasamples = set->aasamples;
        o->aosamples = set->aosamples;
    }
    f->max_passes = o->aasamples + 1;
}

/* A coarse image draws the scene's meshes decimated (made at the drag's first image and
 * kept while their lists do not change) to MS_LIVE_LOD_TRIS triangles, or to
 * MOLSCOPE_LIVE_LOD's number (0: not decimated; for comparisons); a whole image draws them
 * as they are, and the decimated ones are dropped. */
static int lighten(ms_live_frames *f, ms_error *err)
{
    const char *v = getenv("MOLSCOPE_LIVE_LOD");   /* the budget; 0: no decimation */
    char *end = NULL;
    long budget = v && *v ? strtol(v, &end, 10) : MS_LIVE_LOD_TRIS;
    if (end && (*end || budget < 0)) budget = MS_LIVE_LOD_TRIS;
    if (!f->coarse || budget == 0) {
        ms_scene_lod_free(&f->lod);
        f->triangles = ms_scene_triangles(&f->scene);
        return 0;
    }
    return ms_scene_lod_apply(&f->lod, &f->scene, (size_t)budget, &f->triangles, err);
}

/* The raster image of the scene (coarse while the page drags), published with its timing
 * (seconds since t0, when the scene was begun). */
static void raster_image(ms_live_frames *f, ms_gl *gl, double t0)
{
    ms_error err = {{0}};
    ms_image img;
    ms_gl_times t = {0, 0, 0};
    /* while the page drags, a coarse image (half the size each way), and no passes */
    f->coarse = ms_now() < f->interact_until && f->scene.width >= 64 && f->scene.height >= 64;
    if (f->coarse) {
        f->scene.width /= 2;
        f->scene.height /= 2;
        f->rt_pending = 0;
    }
    int rc = lighten(f, &err);
    double t1 = ms_now();         /* the scene's time includes its decimation */
    if (rc == 0 && ms_gl_render(gl, &f->scene, &img, &t, &err) == 0) {
        double t2 = ms_now();
        if (publish(f, &img, 0, &err)) snprintf(f->error, sizeof f->error, "%.200s", err.msg);
        ms_image_free(&img);
        f->timing[0] = t1 - t0;
        f->timing[1] = t.upload;
        f->timing[2] = t.draw + t.readback;
        f->timing[3] = ms_now() - t2;
    } else {
        snprintf(f->error, sizeof f->error, "snapshot: %.200s", err.msg);
    }
}

/* A new scene, and its raster image when a GL display runs; the ray tracer starts on it at
 * the next step (so the raster image is sent first). */
static void restart(ms_live_frames *f)
{
    ms_error err = {{0}};
    double t0 = ms_now();
    drop_scene(f);
    f->error[0] = '\0';
    if (ms_world_build_scene(&f->app->world, &f->scene, &err)) {
        snprintf(f->error, sizeof f->error, "%.200s", err.msg);
        remember(f);
        return;
    }
    f->have_scene = 1;
    remember(f);
    ms_rt_options o;
    rt_settings(f, &o);
    f->scene.aa_samples = o.aasamples;
    f->scene.ao_samples = o.aosamples;
    ms_gl *gl = ms_gl_display_current();
    f->rt_pending = ms_rt_available() && !(gl && f->raster_only);
    if (gl) raster_image(f, gl, t0);
    if (!gl && !ms_rt_available())
        snprintf(f->error, sizeof f->error, "no renderer: no GL display runs and molscope was "
                 "built without Embree (TachyonInternal)");
}

static void begin_rt(ms_live_frames *f)
{
    ms_error err = {{0}};
    ms_rt_options o;
    rt_settings(f, &o);
    f->rt_pending = 0;
    f->rt = ms_rt_session_begin(&f->scene, &o, &err);
    if (!f->rt) snprintf(f->error, sizeof f->error, "TachyonInternal: %.200s", err.msg);
}

static void one_pass(ms_live_frames *f)
{
    ms_error err = {{0}};
    ms_image img;
    ms_rt_session_pass(f->rt);
    if (ms_rt_session_image(f->rt, &img, &err) == 0) {
        if (publish(f, &img, ms_rt_session_passes(f->rt), &err))
            snprintf(f->error, sizeof f->error, "%.200s", err.msg);
        ms_image_free(&img);
    } else {
        snprintf(f->error, sizeof f->error, "TachyonInternal: %.200s", err.msg);
    }
}

int ms_live_frames_step(ms_live_frames *f)
{
    if (ms_live_frames_stale(f)) {
        restart(f);
        /* without a raster image, the first pass is the first image */
        if (f->rt_pending && !ms_gl_display_current()) {
            begin_rt(f);
            if (f->rt) one_pass(f);
        }
    } else if (f->rt_pending) {
        begin_rt(f);
    } else if (f->rt && ms_rt_session_passes(f->rt) < f->max_passes) {
        one_pass(f);
    }
    if (f->rt && ms_rt_session_passes(f->rt) >= f->max_passes) {
        ms_rt_session_end(f->rt);      /* done: the scene is kept for the change check */
        f->rt = NULL;
    }
    return ms_live_frames_stale(f) || f->rt_pending || f->rt != NULL;
}

/* ---------------------------------------------------------------- scheduling */

static void on_idle(ClientData cd)
{
    ms_live_frames *f = cd;
    f->idle_queued = 0;
    if (ms_live_frames_step(f)) {
        f->idle_queued = 1;
        Tcl_DoWhenIdle(on_idle, f);
    }
}

void ms_live_frames_kick(ms_live_frames *f)
{
    if (!f->idle_queued && (ms_live_frames_stale(f) || f->rt_pending || f->rt)) {
        f->idle_queued = 1;
        Tcl_DoWhenIdle(on_idle, f);
    }
}

static void on_check(ClientData cd)
{
    ms_live_frames *f = cd;
    ms_live_frames_kick(f);
    f->timer = Tcl_CreateTimerHandler(CHECK_MS, on_check, f);
}

void ms_live_frames_start(ms_live_frames *f, ms_app *app)
{
    memset(f, 0, sizeof *f);
    f->app = app;
    f->timer = Tcl_CreateTimerHandler(0, on_check, f);
}

void ms_live_frames_stop(ms_live_frames *f)
{
    if (f->timer) Tcl_DeleteTimerHandler((Tcl_TimerToken)f->timer);
    if (f->idle_queued) Tcl_CancelIdleCall(on_idle, f);
    drop_scene(f);
    ms_scene_lod_free(&f->lod);
    free(f->png);
    memset(f, 0, sizeof *f);
}

/* ---------------------------------------------------------------- view changes */

void ms_live_view_init(ms_live_view *v)
{
    memset(v, 0, sizeof *v);
    v->scale = 1.0f;
}

/* A plain decimal number (no spaces, no words such as "inf" or "nan") within [lo, hi]. */
static int parse_bounded(const char *s, double lo, double hi, double *out)
{
    if (!*s || strlen(s) > 32 || strspn(s, "0123456789+-.eE") != strlen(s)) return -1;
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    if (*end || errno || !isfinite(d) || d < lo || d > hi) return -1;
    *out = d;
    return 0;
}

int ms_live_view_set(ms_live_view *v, const char *key, const char *value, ms_error *err)
{
    static const char *const keys[] = {"rx", "ry", "rz", "scale", "tx", "ty", "tz"};
    int k = -1;
    for (int i = 0; i < (int)MS_COUNTOF(keys); i++)
        if (!strcmp(key, keys[i])) k = i;
    if (k < 0) {
        ms_error_set(err, "unknown field '%.40s' (expected rx ry rz scale tx ty tz)", key);
        return -1;
    }
    double lo = k < 3 ? -MS_LIVE_MAX_DEG : k == 3 ? MS_LIVE_MIN_SCALE : -MS_LIVE_MAX_TRANS;
    double hi = k < 3 ? MS_LIVE_MAX_DEG : k == 3 ? MS_LIVE_MAX_SCALE : MS_LIVE_MAX_TRANS, d;
    if (parse_bounded(value, lo, hi, &d)) {
        ms_error_set(err, "%s: '%.40s' is not a number from %g to %g", key, value, lo, hi);
        return -1;
    }
    if (k < 3) v->rot[k] = (float)d;
    else if (k == 3) v->scale = (float)d;
    else v->trans[k - 4] = (float)d;
    return 0;
}

void ms_live_view_apply(ms_app *app, const ms_live_view *v)
{
    for (int k = 0; k < 3; k++)
        if (v->rot[k] != 0.0f) ms_view_rotate_by(&app->world, (char)('x' + k), v->rot[k]);
    if (v->scale != 1.0f) ms_view_scale(&app->world, v->scale, 1);
    if (v->trans[0] != 0.0f || v->trans[1] != 0.0f || v->trans[2] != 0.0f)
        ms_view_translate(&app->world, v->trans[0], v->trans[1], v->trans[2], 1);
}
