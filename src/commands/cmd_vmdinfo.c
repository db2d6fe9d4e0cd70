/* cmd_vmdinfo.c: `vmdinfo`: what program and build this is. `version` answers with the VMD
 * Tcl API level molscope implements, so scripts that test it keep working; `versionmsg`
 * says what is really running. */
#include "config.h"
#include "commands/commands.h"

#include <string.h>
#include <strings.h>
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

static int cmd_vmdinfo(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *keys[] = {"version", "versionmsg", "arch", "options", "compiletime",
                                 "www", "wwwhelp", "authors", "progname"};
    if (objc != 2) {
        Tcl_WrongNumArgs(interp, 1, objv, "version|versionmsg|arch|options|compiletime|www|authors");
        return TCL_ERROR;
    }
    const char *k = Tcl_GetString(objv[1]);
    struct utsname u;
    Tcl_Obj *r = NULL;
    if (!strcasecmp(k, "version")) r = Tcl_NewStringObj(MS_VMD_API_VERSION, -1);
    else if (!strcasecmp(k, "versionmsg"))
        r = Tcl_ObjPrintf("molscope %s (VMD %s Tcl API)", PACKAGE_VERSION, MS_VMD_API_VERSION);
    else if (!strcasecmp(k, "arch")) r = Tcl_NewStringObj(uname(&u) == 0 ? u.machine : "unknown", -1);
    else if (!strcasecmp(k, "options")) r = Tcl_NewStringObj(build_options(), -1);
    else if (!strcasecmp(k, "compiletime")) r = Tcl_NewStringObj(__DATE__ " " __TIME__, -1);
    else if (!strcasecmp(k, "www") || !strcasecmp(k, "wwwhelp")) r = Tcl_NewStringObj("https://molscope.org/", -1);
    else if (!strcasecmp(k, "authors")) r = Tcl_NewStringObj("the molscope developers", -1);
    else if (!strcasecmp(k, "progname")) r = Tcl_NewStringObj("molscope", -1);
    if (!r) {
        Tcl_Obj *msg = Tcl_ObjPrintf("vmdinfo: unknown key '%s': must be", k);
        for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
            Tcl_AppendPrintfToObj(msg, " %s", keys[i]);
        Tcl_SetObjResult(interp, msg);
        return TCL_ERROR;
    }
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

void ms_cmd_vmdinfo_register(ms_app *app)
{
    Tcl_CreateObjCommand(app->interp, "vmdinfo", cmd_vmdinfo, app, NULL);
}
