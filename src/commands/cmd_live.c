/* cmd_live.c: `display live`, the live view of the session in a browser (live/live.h).
 *
 *   display live on ?port? ?-bind addr?   start serving (port 0 or none: a free port), print
 *                                          the URL with its token on stdout and return it
 *   display live off                       stop serving
 *   display live status                    "off", or a dict: url port images passes error
 *
 * Under MPI only rank 0 serves; on the other ranks the command does nothing. */
#include "config.h"
#include "commands/scenecmds.h"
#include "live/live.h"
#include "parallel/parallel.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

#define USAGE "display live: usage: display live on ?port? ?-bind addr? | off | status"

static int live_on(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int port = 0;
    const char *bind = NULL;
    for (int i = 3; i < objc; i++) {
        const char *w = Tcl_GetString(objv[i]);
        if (!strcmp(w, "-bind") && i + 1 < objc) bind = Tcl_GetString(objv[++i]);
        else if (i == 3 && Tcl_GetIntFromObj(NULL, objv[i], &port) == TCL_OK) continue;
        else return ms_cmd_error(interp, "display live on: bad argument '%s': expected ?port? ?-bind addr?", w);
    }
    ms_live_status st;
    ms_error err = {{0}};
    if (ms_live_start(app, port, bind, &st, &err))
        return ms_cmd_error(interp, "display live on: %s", err.msg);
    printf("display live: %s\n", st.url);
    fflush(stdout);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(st.url, -1));
    return TCL_OK;
}

static int live_status(ms_app *app, Tcl_Interp *interp)
{
    ms_live_status st;
    ms_live_get_status(app, &st);
    if (!st.on) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj("off", -1));
        return TCL_OK;
    }
    Tcl_Obj *d = Tcl_NewDictObj();
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("url", -1), Tcl_NewStringObj(st.url, -1));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("port", -1), Tcl_NewIntObj(st.port));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("images", -1), Tcl_NewWideIntObj((Tcl_WideInt)st.images));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("passes", -1), Tcl_NewIntObj(st.passes));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("error", -1), Tcl_NewStringObj(st.error, -1));
    Tcl_SetObjResult(interp, d);
    return TCL_OK;
}

static int disp_live(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc < 3) return ms_cmd_error(interp, USAGE);
    const char *w = Tcl_GetString(objv[2]);
    if (!strcasecmp(w, "status") && objc == 3) return live_status(app, interp);
    if (ms_par_rank() != 0) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj("display live: served by rank 0 only", -1));
        return TCL_OK;
    }
    if (!strcasecmp(w, "on")) {
        char why[300];
        if (!ms_live_available(why, sizeof why)) return ms_cmd_error(interp, "display live on: %s", why);
        return live_on(app, interp, objc, objv);
    }
    if (!strcasecmp(w, "off") && objc == 3) {
        if (ms_live_stop(app)) return ms_cmd_error(interp, "display live off: the live view is not on");
        return TCL_OK;
    }
    return ms_cmd_error(interp, USAGE);
}

void ms_cmd_live_register(ms_app *app)
{
    static const ms_subcmd table[] = {{"live", disp_live}, {NULL, NULL}};
    ms_cmdset_extend_quiet(app, "display", table);
}
