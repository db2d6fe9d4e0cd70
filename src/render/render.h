/* render.h: what a render device is and what the devices share. A device is one struct of
 * function pointers named as VMD's `render` names it; it receives only the Scene and writes a
 * file through base/safewrite (a file is replaced whole or not at all, a symlink is written
 * through, a device or FIFO is written in place; a failure leaves nothing behind). The
 * devices are listed in one table above them (assemble/devices.c); none registers itself.
 *
 * The file exporters live here too: Tachyon (tachyon.c), POV3 (pov3.c), Wavefront
 * (wavefront.c), Raster3D (r3d.c), RenderMan (rib.c), STL (stl.c), VRML-2 and X3D (vrml.c),
 * with what they share in export.h (walk.c hands the last five every primitive). The other devices are snapshot (gl/),
 * TachyonInternal (rt/) and the OpenCL tracer (oclrt/). */
#ifndef MS_RENDER_H
#define MS_RENDER_H

#include <stdio.h>

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
    /* Image devices only (NULL for the file exporters): render the scene into img in memory,
     * as write would before encoding; 0, or -1 with err set and img left empty. */
    int (*image)(const ms_scene *s, ms_image *img, ms_error *err);
    /* Image formats of the post-render command (NULL-terminated; NULL: none), the default
     * one, and the command a format and a sample count give (NULL: the command is fixed). */
    const char *const *formats;
    int default_format;
    void (*cmd_for)(int format, int aasamples, char *buf, size_t size);
} ms_render_device;

/* The file exporters' devices (tachyon.c, pov3.c, wavefront.c, r3d.c, rib.c, stl.c, vrml.c). */
extern const ms_render_device ms_render_tachyon, ms_render_pov3, ms_render_wavefront;
extern const ms_render_device ms_render_raster3d, ms_render_renderman, ms_render_stl;
extern const ms_render_device ms_render_vrml2, ms_render_x3d;

/* For image devices: write the image make renders to path, in the format its name says (TGA
 * for other names, as VMD writes), through base/safewrite, opened before make runs, so that an
 * unwritable path fails before the work. make fills img and returns 0, or sets err and
 * returns non-zero. 0, or -1 with err set and no file left behind. */
typedef int (*ms_render_image_fn)(void *user, ms_image *img, ms_error *err);
int ms_render_write_image(const char *path, ms_render_image_fn make, void *user, ms_error *err);

#endif
