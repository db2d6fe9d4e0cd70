/* gl.h: offscreen OpenGL rasterization of a Scene, with no X server: the OSMesa back-end
 * (Mesa's llvmpipe on any CPU) and the EGL back-end (the EGL device platform on a GPU
 * driver such as NVIDIA's, else Mesa's surfaceless platform). Both draw into a framebuffer
 * object of the image's size through one GL 3.3 core code path, whose functions each context
 * loads from its own library (the two never collide in one program).
 *
 * The display device: `-dispdev osmesa|egl` starts one back-end; `opengl`, `openglpbuffer`
 * and `win` start the best one available (EGL on a GPU, else EGL surfaceless, else OSMesa);
 * `text` and `none` start nothing and `render snapshot` opens the best one on demand. The
 * `snapshot` render device draws the scene at the display size and writes it through
 * image/image.h (PNG, TGA, PPM or BMP by extension; no partial file on failure). */
#ifndef MS_GL_H
#define MS_GL_H

#include <stddef.h>

#include "base/base.h"
#include "image/image.h"
#include "render/render.h"
#include "scene/scene.h"

typedef enum ms_gl_kind { MS_GL_EGL, MS_GL_OSMESA, MS_GL_NKINDS } ms_gl_kind;

/* An offscreen context with its renderer (programs, buffers, framebuffer). */
typedef struct ms_gl ms_gl;

/* Whether a back-end was built in, and the back-ends by name ("egl", "osmesa"). */
int ms_gl_built(ms_gl_kind k);
const char *ms_gl_kind_name(ms_gl_kind k);
int ms_gl_kind_from_name(const char *name);          /* -1 when unknown */

/* Start a back-end: NULL with err saying why (not built, no EGL display, no GL 3.3 ...). */
ms_gl *ms_gl_open(ms_gl_kind k, ms_error *err);
void ms_gl_close(ms_gl *g);
ms_gl_kind ms_gl_kind_of(const ms_gl *g);
/* One line: back-end, platform, GL renderer and version. */
const char *ms_gl_info(const ms_gl *g);
/* 1 when the renderer is a GPU (not llvmpipe or another software rasterizer). */
int ms_gl_hardware(const ms_gl *g);
/* The largest image side the context can draw. */
int ms_gl_max_side(const ms_gl *g);

/* Seconds spent in the phases of one image. */
typedef struct ms_gl_times {
    double upload;       /* display lists into GL buffers */
    double draw;         /* every pass, finished */
    double readback;     /* pixels into the image */
} ms_gl_times;

/* Draw the scene at its size into img (allocated here; free with ms_image_free). 0, or -1
 * with err set (bad size, GL out of memory) and img left empty. t may be NULL. */
int ms_gl_render(ms_gl *g, const ms_scene *s, ms_image *img, ms_gl_times *t, ms_error *err);

/* ---------------------------------------------------------------- the display device */

/* Start the display device a -dispdev word names (osmesa, egl, opengl, openglpbuffer, win).
 * Returns 0 and writes in msg which back-end runs (for opengl/openglpbuffer/win), or -1 with
 * msg giving the reason and a device that works here. */
int ms_gl_display_start(const char *dispdev, char *msg, size_t size);
/* The running display context, started now (the best available) when none runs: the
 * offscreen context that `render snapshot` uses in a text session. NULL with err set. */
ms_gl *ms_gl_display(ms_error *err);
/* The running display context, or NULL; nothing is started. */
ms_gl *ms_gl_display_current(void);
/* Close the display context (at exit). */
void ms_gl_display_close(void);

/* The `snapshot` render device (render/render.h). */
extern const ms_render_device ms_gl_snapshot;

#endif
