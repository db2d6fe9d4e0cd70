/* display.c: the display device (one offscreen context per program, as VMD has one
 * display) and the `snapshot` render device that draws the scene with it and writes the
 * image by the file's extension. */
#include "config.h"
#include "gl/gl.h"
#include "render/render.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

static ms_gl *display;

/* EGL first: it finds a GPU when there is one, and Mesa's surfaceless platform otherwise. */
static ms_gl *open_best(ms_error *err)
{
    ms_error e[MS_GL_NKINDS];
    if (!ms_gl_built(MS_GL_EGL) && !ms_gl_built(MS_GL_OSMESA)) {
        ms_error_set(err, "OpenGL is not built into this molscope (configure found neither "
                          "OSMesa nor EGL; Debian: libosmesa6-dev libegl-dev libgl-dev); the "
                          "file renderers (Tachyon, POV3, Wavefront) still work");
        return NULL;
    }
    for (int k = 0; k < MS_GL_NKINDS; k++) {
        ms_gl *g = ms_gl_open((ms_gl_kind)k, &e[k]);
        if (g) return g;
    }
    ms_error_set(err, "no offscreen OpenGL device starts here (%s; %s)", e[0].msg, e[1].msg);
    return NULL;
}

/* The name of another back-end that starts, for a message; NULL if none does. */
static const char *working_alternative(ms_gl_kind failed)
{
    for (int k = 0; k < MS_GL_NKINDS; k++) {
        ms_error e;
        ms_gl *g = k == (int)failed ? NULL : ms_gl_open((ms_gl_kind)k, &e);
        if (!g) continue;
        ms_gl_close(g);
        return ms_gl_kind_name((ms_gl_kind)k);
    }
    return NULL;
}

static int start_kind(ms_gl_kind k, char *msg, size_t size)
{
    ms_error err;
    display = ms_gl_open(k, &err);
    if (display) {
        snprintf(msg, size, "%s", ms_gl_info(display));
        return 0;
    }
    const char *alt = working_alternative(k);
    if (alt)
        snprintf(msg, size, "%s; -dispdev %s works here", err.msg, alt);
    else
        snprintf(msg, size, "%s; no other OpenGL device starts either: render snapshot cannot "
                            "draw (the file renderers still work)", err.msg);
    return -1;
}

int ms_gl_display_start(const char *dispdev, char *msg, size_t size)
{
    ms_gl_display_close();
    int k = ms_gl_kind_from_name(dispdev);
    if (k >= 0) return start_kind((ms_gl_kind)k, msg, size);
    ms_error err;
    display = open_best(&err);
    snprintf(msg, size, "%s", display ? ms_gl_info(display) : err.msg);
    return display ? 0 : -1;
}

ms_gl *ms_gl_display(ms_error *err)
{
    if (!display) display = open_best(err);
    return display;
}

ms_gl *ms_gl_display_current(void)
{
    return display;
}

void ms_gl_display_close(void)
{
    ms_gl_close(display);
    display = NULL;
}

/* ---------------------------------------------------------------- render snapshot */

static int snapshot_image(void *user, ms_image *img, ms_error *err)
{
    ms_gl *g = ms_gl_display(err);
    return !g || ms_gl_render(g, user, img, NULL, err) ? -1 : 0;
}

static int snapshot_scene_image(const ms_scene *s, ms_image *img, ms_error *err)
{
    return snapshot_image((void *)s, img, err);
}

/* The format by the file's extension, TGA for others, as every image device picks it. */
static int snapshot_write(const ms_scene *s, const char *path, ms_error *err)
{
    return ms_render_write_image(path, snapshot_image, (void *)s, err);
}

const ms_render_device ms_gl_snapshot = {
    .name = "snapshot",
    .description = "the display's image, drawn offscreen with OpenGL (OSMesa or EGL)",
    .default_cmd = "display %s",
    .has_aa = 0,
    .aasamples = 0,
    .aosamples = 0,
    .write = snapshot_write,
    .image = snapshot_scene_image,
};
