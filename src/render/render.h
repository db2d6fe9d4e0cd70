/* render.h: the devices `render` names, VMD's way: one struct of function pointers per device,
 * registered by name (Tachyon, POV3 and Wavefront here; snapshot, TachyonInternal and the
 * OpenCL tracer register themselves the same way). A device receives only the Scene.
 *
 * `render <method> <file> ?cmd...?` builds the scene, has the device write the file (through
 * base/safewrite: a file is replaced whole or not at all, a symlink is written through, a
 * device or FIFO is written in place), then runs the
 * optional post-render shell command with %s, %w and %h replaced by the file name and the
 * display size. Each device keeps per-application settings: its default post-render command
 * (`render options`, `render default`) and antialiasing / ambient-occlusion samples. */
#ifndef MS_RENDER_H
#define MS_RENDER_H

#include <stdio.h>

#include "app/app.h"
#include "base/safewrite.h"
#include "image/image.h"
#include "scene/scene.h"

typedef struct ms_render_device {
    const char *name;              /* VMD's render method name ("Tachyon") */
    const char *description;
    const char *default_cmd;       /* VMD's default post-render command (render default) */
    int has_aa;                    /* uses antialiasing samples */
    int aasamples, aosamples;      /* defaults */
    /* Write the scene to path; 0, or -1 with err set and no file left behind. */
    int (*write)(const ms_scene *s, const char *path, ms_error *err);
    /* Image formats of the post-render command (NULL-terminated; NULL: none), the default
     * one, and the command a format and a sample count give (NULL: the command is fixed). */
    const char *const *formats;
    int default_format;
    void (*cmd_for)(int format, int aasamples, char *buf, size_t size);
} ms_render_device;

/* Register a device (kept by pointer; first registration of a name wins). */
int ms_render_register(const ms_render_device *dev);
/* The registered devices, in registration order. */
size_t ms_render_count(void);
const ms_render_device *ms_render_device_at(size_t i);
/* A device by name, case-insensitively; NULL when unknown. */
const ms_render_device *ms_render_find(const char *name);
/* Register the devices built into molscope: the file exporters (Tachyon, POV3, Wavefront)
 * and the TachyonInternal ray tracer (rt/rt.h). */
void ms_render_register_builtin(void);

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

/* Render the current scene with a device to a file, then run post_cmd (may be NULL). */
int ms_render(ms_app *app, const ms_render_device *dev, const char *path, const char *post_cmd,
              ms_error *err);
/* The post-render command with %s, %w, %h replaced (malloc'd; NULL on no memory). */
char *ms_render_expand_cmd(const char *cmd, const char *path, int w, int h);

/* For image devices: write the image make renders to path, in the format its name says (TGA
 * for other names, as VMD writes), through base/safewrite, opened before make runs, so that an
 * unwritable path fails before the work. make fills img and returns 0, or sets err and
 * returns non-zero. 0, or -1 with err set and no file left behind. */
typedef int (*ms_render_image_fn)(void *user, ms_image *img, ms_error *err);
int ms_render_write_image(const char *path, ms_render_image_fn make, void *user, ms_error *err);

#endif
