/* devices.h: the render devices by name, their per-application settings and `render` itself.
 *
 * The devices are one table (devices.c) listing each device's struct (render/render.h), in
 * VMD's `render list` order: snapshot (gl/), Tachyon, TachyonInternal (rt/), the OpenCL tracer
 * (oclrt/), POV3 and Wavefront. A device keeps per-application settings: its post-render
 * command (`render options`, `render default`), antialiasing and ambient-occlusion samples and
 * image format.
 *
 * `render <method> <file> ?cmd...?` builds the scene, has the device write the file, then
 * runs the optional post-render shell command with %s, %w and %h replaced by the file name
 * and the display size. */
#ifndef MS_ASSEMBLE_DEVICES_H
#define MS_ASSEMBLE_DEVICES_H

#include "assemble/world.h"
#include "render/render.h"

/* The devices, in `render list` order. */
size_t ms_render_count(void);
const ms_render_device *ms_render_device_at(size_t i);
/* A device by name, case-insensitively; NULL when unknown. */
const ms_render_device *ms_render_find(const char *name);
/* For a name VMD 1.9.4 has for an engine molscope lacks (TachyonLOSPRayInternal, the OptiX
 * interactive and ANARI names), the device that stands in for it; NULL otherwise. Not in
 * `render list`, which names the engines there are, as VMD's does. */
const ms_render_device *ms_render_find_alias(const char *name);

/* Per-application settings of every device. */
typedef struct ms_render_setting {
    const ms_render_device *dev;
    char *cmd;                     /* current post-render command (render options) */
    int aasamples, aosamples;
    int format;                    /* index in dev->formats */
} ms_render_setting;

typedef struct ms_renderers {
    ms_render_setting *list;
    size_t n, cap;
} ms_renderers;

ms_renderers *ms_renderers_new(void);
void ms_renderers_free(ms_renderers *r);
/* The settings of a device (created with its defaults on first use); NULL on no memory. */
ms_render_setting *ms_render_setting_of(ms_renderers *r, const ms_render_device *dev);
int ms_render_set_cmd(ms_render_setting *set, const char *cmd);
/* Change the samples (a negative count leaves one as it is); a post-render command the device
 * generated follows them, one the user set is kept. 0, or -1 when memory runs out. */
int ms_render_set_samples(ms_render_setting *set, int aasamples, int aosamples);
/* Choose an image format by name (case-insensitive); the post-render command is remade for
 * it, as VMD does. -1 when the device has no such format (or no memory). */
int ms_render_set_format(ms_render_setting *set, const char *name);

/* Render the world's scene with a device to a file, then run post_cmd (may be NULL). */
int ms_render(ms_world *w, const ms_render_device *dev, const char *path, const char *post_cmd,
              ms_error *err);
/* Render the world's scene with an image device into img, in memory (the image `render`
 * would write; the caller frees it). 0, or -1 with err set (a file exporter, a failure). */
int ms_render_image(ms_world *w, const ms_render_device *dev, ms_image *img, ms_error *err);
/* The post-render command with %s, %w, %h replaced (malloc'd; NULL on no memory). */
char *ms_render_expand_cmd(const char *cmd, const char *path, int w, int h);

#endif
