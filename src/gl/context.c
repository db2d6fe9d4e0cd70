/* context.c: starting and closing offscreen contexts of either back-end, switching between
 * them, and drawing a scene into an image (render, then read the pixels back top row
 * first). */
#include "config.h"
#include "gl/glrender.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const kind_names[MS_GL_NKINDS] = {"egl", "osmesa"};

/* Sides beyond this are refused even where GL takes them: a 16384 x 16384 image already
 * needs 2 GB of framebuffer and 800 MB of pixels. */
#define MS_GL_MAX_SIDE 16384

static ms_gl *current;      /* the context current in the (one) rendering thread */

int ms_gl_built(ms_gl_kind k)
{
#ifdef MS_HAVE_EGL
    if (k == MS_GL_EGL) return 1;
#endif
#ifdef MS_HAVE_OSMESA
    if (k == MS_GL_OSMESA) return 1;
#endif
    return 0;
}

const char *ms_gl_kind_name(ms_gl_kind k)
{
    return k < MS_GL_NKINDS ? kind_names[k] : "?";
}

int ms_gl_kind_from_name(const char *name)
{
    for (int k = 0; k < MS_GL_NKINDS; k++)
        if (!strcasecmp(name, kind_names[k])) return k;
    return -1;
}

static int backend_init(ms_gl *g, ms_error *err)
{
#ifdef MS_HAVE_EGL
    if (g->kind == MS_GL_EGL) return ms_gl_egl_init(g, err);
#endif
#ifdef MS_HAVE_OSMESA
    if (g->kind == MS_GL_OSMESA) return ms_gl_osmesa_init(g, err);
#endif
    ms_error_set(err, "%s: not built into this molscope (configure found no %s; Debian: %s)",
                 ms_gl_kind_name(g->kind), g->kind == MS_GL_EGL ? "EGL" : "OSMesa",
                 g->kind == MS_GL_EGL ? "libegl-dev libgl-dev" : "libosmesa6-dev libgl-dev");
    return -1;
}

/* Version, renderer, size limits; 3.3 at least. */
static int describe(ms_gl *g, ms_error *err)
{
    const char *ver = (const char *)g->f.GetString(GL_VERSION);
    const char *ren = (const char *)g->f.GetString(GL_RENDERER);
    int major = 0, minor = 0;
    if (!ver || sscanf(ver, "%d.%d", &major, &minor) != 2 || major * 10 + minor < 33) {
        ms_error_set(err, "%s: OpenGL %s; 3.3 core is needed", g->info, ver ? ver : "(unknown)");
        return -1;
    }
    if (!ren) ren = "(unknown renderer)";
    g->hardware = !strstr(ren, "llvmpipe") && !strstr(ren, "softpipe") && !strstr(ren, "SWR") &&
                  !strstr(ren, "Software");
    GLint rb = 0, tex = 0, vp[2] = {0, 0};
    g->f.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    g->f.GetIntegerv(GL_MAX_TEXTURE_SIZE, &tex);
    g->f.GetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    g->max_side = MS_MIN(MS_MIN(MS_MIN(rb, tex), MS_MIN(vp[0], vp[1])), MS_GL_MAX_SIDE);
    size_t n = strlen(g->info);
    snprintf(g->info + n, sizeof g->info - n, ": %s, OpenGL %s", ren, ver);
    return 0;
}

ms_gl *ms_gl_open(ms_gl_kind k, ms_error *err)
{
    if (k >= MS_GL_NKINDS) {
        ms_error_set(err, "no such OpenGL back-end");
        return NULL;
    }
    ms_gl *g = calloc(1, sizeof *g);
    if (!g) {
        ms_error_set(err, "%s: out of memory", kind_names[k]);
        return NULL;
    }
    g->kind = k;
    if (current && current->release) current->release(current);
    current = NULL;
    if (backend_init(g, err) == 0) {
        current = g;
        g->loaded = 1;
        if (describe(g, err) == 0 && ms_glr_init(g, err) == 0) return g;
    }
    ms_gl_close(g);
    return NULL;
}

void ms_gl_close(ms_gl *g)
{
    if (!g) return;
    if (g->loaded && ms_gl_use(g, NULL) == 0) ms_glr_free(g);
    if (g->destroy) g->destroy(g);
    if (current == g) current = NULL;
    free(g);
}

int ms_gl_use(ms_gl *g, ms_error *err)
{
    ms_error scratch;
    if (current == g) return 0;
    if (current && current->release) current->release(current);
    current = NULL;
    if (g->make_current(g, err ? err : &scratch)) return -1;
    current = g;
    return 0;
}

ms_gl_kind ms_gl_kind_of(const ms_gl *g)
{
    return g->kind;
}

const char *ms_gl_info(const ms_gl *g)
{
    return g->info;
}

int ms_gl_hardware(const ms_gl *g)
{
    return g->hardware;
}

int ms_gl_max_side(const ms_gl *g)
{
    return g->max_side;
}

/* ---------------------------------------------------------------- one image */

static int check_size(const ms_gl *g, const ms_scene *s, ms_error *err)
{
    if (s->width < 1 || s->height < 1 || s->width > g->max_side || s->height > g->max_side) {
        ms_error_set(err, "image size %dx%d is outside what %s draws (1 to %d pixels a side)",
                     s->width, s->height, kind_names[g->kind], g->max_side);
        return -1;
    }
    return 0;
}

/* GL rows run bottom to top; images top to bottom. */
static int read_pixels(ms_gl *g, ms_image *img, ms_error *err)
{
    size_t row = 3 * (size_t)img->width;
    g->f.BindFramebuffer(GL_READ_FRAMEBUFFER, g->r.fbo);
    g->f.ReadBuffer(GL_COLOR_ATTACHMENT0);
    g->f.PixelStorei(GL_PACK_ALIGNMENT, 1);
    g->f.ReadPixels(0, 0, img->width, img->height, GL_RGB, GL_UNSIGNED_BYTE, img->rgb);
    GLenum e = g->f.GetError();
    if (e != GL_NO_ERROR) {
        ms_error_set(err, "%s: reading the image back failed (GL error 0x%04x)",
                     kind_names[g->kind], e);
        return -1;
    }
    uint8_t *tmp = malloc(row);
    if (!tmp) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (int y = 0; y < img->height / 2; y++) {
        uint8_t *a = img->rgb + (size_t)y * row;
        uint8_t *b = img->rgb + (size_t)(img->height - 1 - y) * row;
        memcpy(tmp, a, row);
        memcpy(a, b, row);
        memcpy(b, tmp, row);
    }
    free(tmp);
    return 0;
}

int ms_gl_render(ms_gl *g, const ms_scene *s, ms_image *img, ms_gl_times *t, ms_error *err)
{
    ms_gl_times scratch;
    if (!t) t = &scratch;
    memset(t, 0, sizeof *t);
    memset(img, 0, sizeof *img);
    if (check_size(g, s, err) || ms_gl_use(g, err) ||
        ms_glr_framebuffer(g, s->width, s->height, err) || ms_glr_draw_scene(g, s, t, err) ||
        ms_image_alloc(img, s->width, s->height, err))
        return -1;
    double t0 = ms_now();
    if (read_pixels(g, img, err)) {
        ms_image_free(img);
        return -1;
    }
    t->readback = ms_now() - t0;
    return 0;
}
