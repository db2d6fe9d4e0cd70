/* nogl.c: the GL entry points of a build with neither OSMesa nor EGL: every back-end
 * reports that it is not built. */
#include "config.h"
#include "gl/gl.h"

#include <strings.h>

static const char *const kind_names[MS_GL_NKINDS] = {"egl", "osmesa"};

int ms_gl_built(ms_gl_kind k)
{
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

ms_gl *ms_gl_open(ms_gl_kind k, ms_error *err)
{
    ms_error_set(err, "%s: not built into this molscope (configure found neither OSMesa nor "
                      "EGL; Debian: libosmesa6-dev libegl-dev libgl-dev)", ms_gl_kind_name(k));
    return NULL;
}

void ms_gl_close(ms_gl *g) {}
ms_gl_kind ms_gl_kind_of(const ms_gl *g) { return MS_GL_EGL; }
const char *ms_gl_info(const ms_gl *g) { return ""; }
int ms_gl_hardware(const ms_gl *g) { return 0; }
int ms_gl_max_side(const ms_gl *g) { return 0; }

int ms_gl_render(ms_gl *g, const ms_scene *s, ms_image *img, ms_gl_times *t, ms_error *err)
{
    ms_error_set(err, "OpenGL is not built into this molscope");
    return -1;
}
