/* cmd_vmdinfo.c: `vmdinfo`: what program and build this is. `version` answers with the VMD
 * Tcl API level molscope implements, so scripts that test it keep working; `versionmsg`
 * says what is really running. */
#include "config.h"
#include "commands/commands.h"

#include <sys/utsname.h>

#define MS_VMD_API_VERSION "1.9.4"

static const char *build_options(void)
{
    return "TCL PNG PTHREADS"
#ifdef MS_HAVE_EMBREE
           " EMBREE"
#endif
#ifdef MS_HAVE_OSMESA
           " OSMESA"
#endif
#ifdef MS_HAVE_EGL
           " EGL"
#endif
#ifdef MS_HAVE_OPENCL
           " OPENCL"
#endif
#ifdef MS_HAVE_MPI
           " MPI"
#endif
#ifdef MS_FFMPEG_PATH
           " FFMPEG"
#endif
        ;
}

typedef enum { K_VERSION, K_VERSIONMSG, K_ARCH, K_OPTIONS, K_COMPILETIME, K_WWW, K_WWWHELP,
               K_AUTHORS, K_PROGNAME } key;

/* vmdinfo <key>: each key is a subcommand of no arguments */
static int vmdinfo_key(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);

static const ms_subcmd vmdinfo_table[] = {
    {"version", vmdinfo_key, 0, 0, ""},     {"versionmsg", vmdinfo_key, 0, 0, ""},
    {"arch", vmdinfo_key, 0, 0, ""},        {"options", vmdinfo_key, 0, 0, ""},
    {"compiletime", vmdinfo_key, 0, 0, ""}, {"www", vmdinfo_key, 0, 0, ""},
    {"wwwhelp", vmdinfo_key, 0, 0, ""},     {"authors", vmdinfo_key, 0, 0, ""},
    {"progname", vmdinfo_key, 0, 0, ""},    {NULL, NULL, 0, 0, NULL}};

static int vmdinfo_key(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    struct utsname u;
    Tcl_Obj *r = NULL;
    switch ((key)ms_args_find(vmdinfo_table, sizeof *vmdinfo_table, Tcl_GetString(objv[1]))) {
    case K_VERSION: r = Tcl_NewStringObj(MS_VMD_API_VERSION, -1); break;
    case K_VERSIONMSG:
        r = Tcl_ObjPrintf("molscope %s (VMD %s Tcl API)", PACKAGE_VERSION, MS_VMD_API_VERSION);
        break;
    case K_ARCH: r = Tcl_NewStringObj(uname(&u) == 0 ? u.machine : "unknown", -1); break;
    case K_OPTIONS: r = Tcl_NewStringObj(build_options(), -1); break;
    case K_COMPILETIME: r = Tcl_NewStringObj(__DATE__ " " __TIME__, -1); break;
    case K_WWW: case K_WWWHELP: r = Tcl_NewStringObj("https://molscope.org/", -1); break;
    case K_AUTHORS: r = Tcl_NewStringObj("the molscope developers", -1); break;
    case K_PROGNAME: r = Tcl_NewStringObj("molscope", -1); break;
    }
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

void ms_cmd_vmdinfo_register(ms_app *app)
{
    ms_cmdset_create(app, "vmdinfo", vmdinfo_table);
    ms_cmdset_quiet(app, "vmdinfo");
}
