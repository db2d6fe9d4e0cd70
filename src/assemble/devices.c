/* devices.c: the render devices in `render list` order (one table, as rep/methods.c lists
 * the drawing methods: adding a device is its file and a line below), their per-application
 * settings, and `render`'s sequence: build the scene, write, run the post-render command. */
#include "config.h"
#include "assemble/devices.h"
#include "gl/gl.h"
#include "oclrt/oclrt.h"
#include "rt/rt.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---------------------------------------------------------------- the table */

static const ms_render_device *const devices[] = {
    &ms_gl_snapshot,                /* first in `render list`, as in VMD */
    &ms_render_tachyon,
    &ms_render_tachyon_internal,
    &ms_render_tachyon_ocl,
    &ms_render_tachyon_optix,
    &ms_render_pov3,
    &ms_render_wavefront,
    &ms_render_raster3d,
    &ms_render_renderman,
    &ms_render_stl,
    &ms_render_vrml2,
    &ms_render_x3d,
};

size_t ms_render_count(void)
{
    return MS_COUNTOF(devices);
}

const ms_render_device *ms_render_device_at(size_t i)
{
    return i < MS_COUNTOF(devices) ? devices[i] : NULL;
}

const ms_render_device *ms_render_find(const char *name)
{
    for (size_t i = 0; i < MS_COUNTOF(devices); i++)
        if (!strcasecmp(devices[i]->name, name)) return devices[i];
    return NULL;
}

/* VMD 1.9.4's render methods for engines molscope has no copy of, and the engine here that
 * makes the closest picture: the OSPRay tracer runs on the CPU, OptiX and ANARI on a GPU. */
static const struct {
    const char *name, *target;
} aliases[] = {
    {"TachyonLOSPRayInternal", "TachyonInternal"},
    {"TachyonLOSPRayInteractive", "TachyonInternal"},
    {"TachyonLOptiXInteractive", "TachyonLOpenCLInternal"},
    {"TachyonLOptiXInternalRTX", "TachyonLOpenCLInternal"},
    {"TachyonLANARIInternal", "TachyonLOpenCLInternal"},
    {"TachyonLANARIInteractive", "TachyonLOpenCLInternal"},
    {"ANARIInternal", "TachyonLOpenCLInternal"},
    {"ANARIInteractive", "TachyonLOpenCLInternal"},
};

const ms_render_device *ms_render_find_alias(const char *name)
{
    for (size_t i = 0; i < MS_COUNTOF(aliases); i++)
        if (!strcasecmp(aliases[i].name, name)) return ms_render_find(aliases[i].target);
    return NULL;
}

/* ---------------------------------------------------------------- settings */

ms_renderers *ms_renderers_new(void)
{
    return calloc(1, sizeof(ms_renderers));
}

void ms_renderers_free(ms_renderers *r)
{
    if (!r) return;
    for (size_t i = 0; i < r->n; i++) free(r->list[i].cmd);
    free(r->list);
    free(r);
}

ms_render_setting *ms_render_setting_of(ms_renderers *r, const ms_render_device *dev)
{
    for (size_t i = 0; i < r->n; i++)
        if (r->list[i].dev == dev) return &r->list[i];
    char *cmd = ms_strdup(dev->default_cmd);
    if (!cmd || ms_grow((void **)&r->list, &r->cap, r->n + 1, sizeof *r->list)) {
        free(cmd);
        return NULL;
    }
    ms_render_setting *s = &r->list[r->n++];
    s->dev = dev;
    s->cmd = cmd;
    s->aasamples = dev->aasamples;
    s->aosamples = dev->aosamples;
    s->format = dev->default_format;
    return s;
}

/* The command the device makes for the current settings; 0 when it has none. */
static int generated_cmd(const ms_render_setting *s, char *buf, size_t size)
{
    if (!s->dev->cmd_for) return 0;
    s->dev->cmd_for(s->format, s->aasamples, buf, size);
    return 1;
}

int ms_render_set_samples(ms_render_setting *set, int aasamples, int aosamples)
{
    char gen[1024];
    int follow = generated_cmd(set, gen, sizeof gen) && !strcmp(gen, set->cmd);
    if (aasamples >= 0) set->aasamples = aasamples;
    if (aosamples >= 0) set->aosamples = aosamples;
    if (!follow) return 0;
    generated_cmd(set, gen, sizeof gen);
    return ms_render_set_cmd(set, gen);
}

int ms_render_set_format(ms_render_setting *set, const char *name)
{
    const char *const *f = set->dev->formats;
    for (int i = 0; f && f[i]; i++) {
        if (strcasecmp(f[i], name)) continue;
        char gen[1024];
        set->format = i;
        return generated_cmd(set, gen, sizeof gen) ? ms_render_set_cmd(set, gen) : 0;
    }
    return -1;
}

int ms_render_set_cmd(ms_render_setting *set, const char *cmd)
{
    char *c = ms_strdup(cmd);
    if (!c) return -1;
    free(set->cmd);
    set->cmd = c;
    return 0;
}

/* ---------------------------------------------------------------- render */

char *ms_render_expand_cmd(const char *cmd, const char *path, int w, int h)
{
    char ws[16], hs[16];
    snprintf(ws, sizeof ws, "%d", w);
    snprintf(hs, sizeof hs, "%d", h);
    size_t cap = strlen(cmd) + 1, n = 0;
    for (const char *p = cmd; *p; p++)
        if (p[0] == '%' && (p[1] == 's' || p[1] == 'w' || p[1] == 'h')) cap += strlen(path) + 16;
    char *out = malloc(cap);
    if (!out) return NULL;
    for (const char *p = cmd; *p; p++) {
        const char *sub = NULL;
        if (p[0] == '%' && p[1] == 's') sub = path;
        else if (p[0] == '%' && p[1] == 'w') sub = ws;
        else if (p[0] == '%' && p[1] == 'h') sub = hs;
        if (sub) {
            size_t l = strlen(sub);
            memcpy(out + n, sub, l);
            n += l;
            p++;
        } else {
            out[n++] = *p;
        }
    }
    out[n] = '\0';
    return out;
}

/* The world's scene with the device's sample counts. */
static int device_scene(ms_world *w, const ms_render_device *dev, ms_scene *scene,
                        ms_error *err)
{
    ms_render_setting *set = ms_render_setting_of(w->renderers, dev);
    if (!set) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    if (ms_world_build_scene(w, scene, err)) return -1;
    scene->aa_samples = set->aasamples;
    scene->ao_samples = set->aosamples;
    return 0;
}

int ms_render_image(ms_world *w, const ms_render_device *dev, ms_image *img, ms_error *err)
{
    if (!dev->image) {
        ms_error_set(err, "%s writes a scene file, not an image (render it to a file)",
                     dev->name);
        return -1;
    }
    ms_scene scene;
    if (device_scene(w, dev, &scene, err)) return -1;
    int rc = dev->image(&scene, img, err);
    ms_scene_free(&scene);
    return rc;
}

int ms_render(ms_world *w, const ms_render_device *dev, const char *path, const char *post_cmd,
              ms_error *err)
{
    ms_scene scene;
    if (device_scene(w, dev, &scene, err)) return -1;
    int rc = dev->write(&scene, path, err);
    ms_scene_free(&scene);
    if (rc || !post_cmd || !*post_cmd) return rc;
    char *cmd = ms_render_expand_cmd(post_cmd, path, w->width, w->height);
    if (!cmd) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    /* As VMD: the command's own exit status is not an error of `render`. */
    fflush(stdout);
    if (system(cmd) == -1) {
        ms_error_set(err, "cannot run the post-render command '%s': %s", cmd, strerror(errno));
        rc = -1;
    }
    free(cmd);
    return rc;
}
