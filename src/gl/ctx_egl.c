/* ctx_egl.c: the EGL back-end. Displays are tried in order: the GPUs of the EGL device
 * platform (EGL_EXT_platform_device: NVIDIA's driver, Mesa's DRM devices), then Mesa's
 * surfaceless platform, then a software device; the first that gives a GL 3.3 core context
 * wins. The context is made current on a 1x1 pbuffer (a config with EGL_PBUFFER_BIT) or, on
 * a display without one, on no surface at all (EGL_KHR_surfaceless_context); the renderer
 * draws into its own framebuffer object either way. Only libEGL is linked: GL functions come
 * from eglGetProcAddress. */
#include "config.h"
#include "gl/glrender.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct egl {
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface surf;
} egl;

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: return "EGL error";
    }
}

static ms_glproc getproc(const char *name)
{
    return (ms_glproc)eglGetProcAddress(name);
}

static int has_ext(const char *list, const char *ext)
{
    size_t n = strlen(ext);
    for (const char *p = list; p && (p = strstr(p, ext)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    return 0;
}

static int make_current(ms_gl *g, ms_error *err)
{
    egl *e = g->impl;
    if (eglMakeCurrent(e->dpy, e->surf, e->surf, e->ctx)) return 0;
    ms_error_set(err, "egl: cannot make the context current (%s)", egl_error_name(eglGetError()));
    return -1;
}

static void unbind(ms_gl *g)
{
    egl *e = g->impl;
    eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

static void release(egl *e)
{
    if (e->dpy == EGL_NO_DISPLAY) return;
    eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (e->surf != EGL_NO_SURFACE) eglDestroySurface(e->dpy, e->surf);
    if (e->ctx != EGL_NO_CONTEXT) eglDestroyContext(e->dpy, e->ctx);
    eglTerminate(e->dpy);
    e->dpy = EGL_NO_DISPLAY;
    e->ctx = EGL_NO_CONTEXT;
    e->surf = EGL_NO_SURFACE;
}

static void destroy(ms_gl *g)
{
    egl *e = g->impl;
    if (!e) return;
    release(e);
    eglReleaseThread();
    free(e);
    g->impl = NULL;
}

/* A GL 3.3 core context on an initialised display, current on a pbuffer or no surface. */
static int make_context(egl *e, char *why, size_t size)
{
    static const EGLint pbuf_cfg[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                                      EGL_BLUE_SIZE, 8, EGL_NONE};
    static const EGLint any_cfg[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_NONE};
    static const EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    static const EGLint pbuf_attrs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    int pbuffer = eglChooseConfig(e->dpy, pbuf_cfg, &cfg, 1, &n) && n > 0;
    const char *exts = eglQueryString(e->dpy, EGL_EXTENSIONS);
    int surfaceless = has_ext(exts, "EGL_KHR_surfaceless_context");
    if (!pbuffer && !(surfaceless && eglChooseConfig(e->dpy, any_cfg, &cfg, 1, &n) && n > 0)) {
        snprintf(why, size, "no OpenGL config with a pbuffer");
        return -1;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(why, size, "no desktop OpenGL (%s)", egl_error_name(eglGetError()));
        return -1;
    }
    e->ctx = eglCreateContext(e->dpy, cfg, EGL_NO_CONTEXT, ctx_attrs);
    if (e->ctx == EGL_NO_CONTEXT) {
        snprintf(why, size, "no OpenGL 3.3 core context (%s)", egl_error_name(eglGetError()));
        return -1;
    }
    if (pbuffer) e->surf = eglCreatePbufferSurface(e->dpy, cfg, pbuf_attrs);
    if (pbuffer && e->surf == EGL_NO_SURFACE) {
        snprintf(why, size, "no pbuffer (%s)", egl_error_name(eglGetError()));
        return -1;
    }
    if (!eglMakeCurrent(e->dpy, e->surf, e->surf, e->ctx)) {
        snprintf(why, size, "cannot make the context current (%s)", egl_error_name(eglGetError()));
        return -1;
    }
    return 0;
}

/* Try one display; 0 when it gave a current context. */
static int try_display(egl *e, EGLDisplay dpy, char *why, size_t size)
{
    EGLint major, minor;
    if (dpy == EGL_NO_DISPLAY) {
        snprintf(why, size, "no display");
        return -1;
    }
    if (!eglInitialize(dpy, &major, &minor)) {
        snprintf(why, size, "cannot initialise (%s)", egl_error_name(eglGetError()));
        return -1;
    }
    e->dpy = dpy;
    if (make_context(e, why, size) == 0) return 0;
    release(e);
    return -1;
}

typedef struct cands {
    EGLDeviceEXT dev[16];
    int n;
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display;
    PFNEGLQUERYDEVICESTRINGEXTPROC dev_string;
} cands;

static int is_software(const cands *c, EGLDeviceEXT d)
{
    return has_ext(c->dev_string(d, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

static void find_devices(cands *c)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    memset(c, 0, sizeof *c);
    if (!has_ext(client, "EGL_EXT_platform_base")) return;
    c->get_display = (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    PFNEGLQUERYDEVICESEXTPROC query =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    c->dev_string = (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    if (!c->get_display || !query || !c->dev_string || !has_ext(client, "EGL_EXT_platform_device"))
        return;
    EGLint n = 0;
    if (query(16, c->dev, &n) && n > 0) c->n = n;
}

/* The platforms in order of preference; platform names what worked. */
static int open_any(egl *e, char *platform, size_t psize, ms_error *err)
{
    cands c;
    char why[256] = "no EGL display", last[256] = "";
    find_devices(&c);
    for (int soft = 0; soft < 2; soft++) {
        for (int i = 0; i < c.n; i++) {
            if (is_software(&c, c.dev[i]) != soft) continue;
            EGLDisplay dpy = c.get_display(EGL_PLATFORM_DEVICE_EXT, c.dev[i], NULL);
            if (try_display(e, dpy, why, sizeof why) == 0) {
                const char *file = c.dev_string(c.dev[i], EGL_DRM_DEVICE_FILE_EXT);
                snprintf(platform, psize, "device %d%s%s", i, file ? " " : "", file ? file : "");
                return 0;
            }
            snprintf(last, sizeof last, "device %d: %s", i, why);
        }
        const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (soft || !c.get_display || !has_ext(client, "EGL_MESA_platform_surfaceless")) continue;
        if (try_display(e, c.get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL),
                        why, sizeof why) == 0) {
            snprintf(platform, psize, "surfaceless");
            return 0;
        }
        snprintf(last, sizeof last, "surfaceless: %s", why);
    }
    if (try_display(e, eglGetDisplay(EGL_DEFAULT_DISPLAY), why, sizeof why) == 0) {
        snprintf(platform, psize, "default display");
        return 0;
    }
    ms_error_set(err, "egl: no display gives an OpenGL 3.3 core context (%s%s%s)", last,
                 *last ? "; default display: " : "default display: ", why);
    return -1;
}

int ms_gl_egl_init(ms_gl *g, ms_error *err)
{
    egl *e = calloc(1, sizeof *e);
    if (!e) {
        ms_error_set(err, "egl: out of memory");
        return -1;
    }
    e->dpy = EGL_NO_DISPLAY;
    e->ctx = EGL_NO_CONTEXT;
    e->surf = EGL_NO_SURFACE;
    g->impl = e;
    g->make_current = make_current;
    g->release = unbind;
    g->destroy = destroy;
    char platform[128];
    if (open_any(e, platform, sizeof platform, err)) return -1;
    snprintf(g->info, sizeof g->info, "egl %s", platform);
    return ms_glfn_load(&g->f, getproc, err);
}
