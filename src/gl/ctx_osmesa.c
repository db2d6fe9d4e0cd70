/* ctx_osmesa.c: the OSMesa back-end: a GL 3.3 core context of Mesa's llvmpipe in memory,
 * made current on a 1x1 buffer it owns (the renderer draws into its own framebuffer object,
 * as with EGL). Functions come from OSMesaGetProcAddress. */
#include "config.h"
#include "gl/glrender.h"

#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct osm {
    OSMesaContext ctx;
    unsigned char pixel[16];
} osm;

static ms_glproc getproc(const char *name)
{
    return (ms_glproc)OSMesaGetProcAddress(name);
}

static int make_current(ms_gl *g, ms_error *err)
{
    osm *o = g->impl;
    if (OSMesaMakeCurrent(o->ctx, o->pixel, GL_UNSIGNED_BYTE, 1, 1)) return 0;
    ms_error_set(err, "osmesa: cannot make the context current");
    return -1;
}

static void release(ms_gl *g)
{
    OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
}

static void destroy(ms_gl *g)
{
    osm *o = g->impl;
    if (!o) return;
    release(g);
    OSMesaDestroyContext(o->ctx);
    free(o);
    g->impl = NULL;
}

int ms_gl_osmesa_init(ms_gl *g, ms_error *err)
{
    static const int attrs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                                OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                OSMESA_CONTEXT_MAJOR_VERSION, 3,
                                OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    osm *o = calloc(1, sizeof *o);
    if (!o) {
        ms_error_set(err, "osmesa: out of memory");
        return -1;
    }
    o->ctx = OSMesaCreateContextAttribs(attrs, NULL);
    if (!o->ctx) {
        free(o);
        ms_error_set(err, "osmesa: cannot create an OpenGL 3.3 core context");
        return -1;
    }
    g->impl = o;
    g->make_current = make_current;
    g->release = release;
    g->destroy = destroy;
    snprintf(g->info, sizeof g->info, "osmesa");
    if (make_current(g, err)) return -1;
    return ms_glfn_load(&g->f, getproc, err);
}
