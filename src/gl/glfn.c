/* glfn.c: loading the GL function table of a context (see glfn.h). */
#include "config.h"
#include "gl/glfn.h"

int ms_glfn_load(ms_glfn *f, ms_glproc (*getproc)(const char *name), ms_error *err)
{
#define MS_GLFN_LOAD(type, name)                                                   \
    f->name = (type)getproc("gl" #name);                                           \
    if (!f->name) {                                                                \
        ms_error_set(err, "the GL library has no gl" #name " (OpenGL 3.3 needed)"); \
        return -1;                                                                 \
    }
    MS_GLFN_LIST(MS_GLFN_LOAD)
#undef MS_GLFN_LOAD
    return 0;
}
