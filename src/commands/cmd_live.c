/* cmd_live.c: `display live`, the live view of the session in a browser (live/live.h).
 *
 *   display live on ?port? ?-bind addr?   start serving (port 0 or none: a free port), print
 *                                          the URL with its token on stdout and return it
 *   display live off                       stop serving
 *   display live status                    "off", or a dict: url port images passes error
 *                                          timing (the last raster image's milliseconds:
 *                                          scene, upload, draw and readback, PNG),
 *                                          triangles (mesh triangles it drew) and coarse
 *                                          (1: a drag's image, decimated meshes, half size)
 *   display live mode ?raster|progressive? the page's images: the raster image alone, or
 *                                          refined by ray-traced passes (the default)
 *
 * Under MPI only rank 0 serves; on the other ranks the command does nothing. */
#include "config.h"
#include "commands/scenecmds.h"
#include "live/live.h"
#include "parallel/parallel.h"

#include <limits.h>
#include <stdio.h>

/* Under MPI, ranks other than 0 answer this and do nothing. */
static int served_elsewhere(Tcl_Interp *interp)
{
    Tcl_SetObjResult(interp, Tcl_NewStringObj("display live: served by rank 0 only", -1));
    return TCL_OK;
}

static int live_on(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_opt options[] = {{"-bind", MS_OPT_STRING, 0, 0, 0, 0, NULL},
                                     {NULL, 0, 0, 0, 0, 0, NULL}};
    int port = 0, first = 3;
    const char *bind = NULL;
    char why[300];
    if (ms_par_rank() != 0) return served_elsewhere(interp);
    if (!ms_live_available(why, sizeof why)) return ms_cmd_error(interp, "display live on: %s", why);
    if (objc > 3 && !ms_word_eq(Tcl_GetString(objv[3]), "-bind") &&
        ms_arg_int(interp, objv[first++], "port", INT_MIN, INT_MAX, &port))
        return TCL_ERROR;
    if (ms_args_options(interp, objc, objv, first, options, &bind, NULL)) return TCL_ERROR;
    ms_live_status st;
    ms_error err = {{0}};
    if (ms_live_start(app, port, bind, &st, &err))
        return ms_cmd_error(interp, "display live on: %s", err.msg);
    printf("display live: %s\n", st.url);
    printf("display live: whoever holds this URL (its token) can run any command in this "
           "session from the page's console, as you can at this prompt: share it only as "
           "you would your shell\n");
    fflush(stdout);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(st.url, -1));
    return TCL_OK;
}

static int live_off(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (ms_par_rank() != 0) return served_elsewhere(interp);
    if (ms_live_stop(app)) return ms_cmd_error(interp, "display live off: the live view is not on");
    return TCL_OK;
}

static int live_status(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
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
    Tcl_Obj *t = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < 4; i++) Tcl_ListObjAppendElement(NULL, t, Tcl_NewDoubleObj(st.timing[i] * 1e3));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("timing", -1), t);
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("triangles", -1),
                   Tcl_NewWideIntObj((Tcl_WideInt)st.triangles));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("coarse", -1), Tcl_NewBooleanObj(st.coarse));
    Tcl_SetObjResult(interp, d);
    return TCL_OK;
}

static int live_mode(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const modes[] = {"progressive", "raster", NULL};
    int raster = 0;
    if (objc == 4 && ms_arg_choice(interp, objv[3], modes, "mode", &raster)) return TCL_ERROR;
    if (ms_live_mode(app, objc == 4, &raster))
        return ms_cmd_error(interp, "display live mode: the live view is not on");
    Tcl_SetObjResult(interp, Tcl_NewStringObj(modes[raster], -1));
    return TCL_OK;
}

static int disp_live(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd table[] = {
        {"on", live_on, 0, 3, "?<port>? ?-bind <address>?"},
        {"off", live_off, 0, 0, ""},
        {"status", live_status, 0, 0, ""},
        {"mode", live_mode, 0, 1, "?raster|progressive?"},
        {NULL, NULL, 0, 0, NULL}};
    return ms_args_dispatch(app, interp, objc, objv, 2, table, NULL, NULL);
}

void ms_cmd_live_register(ms_app *app)
{
    static const ms_subcmd table[] = {
        {"live", disp_live, 1, MS_ARGS_ANY, "on ?<port>? ?-bind <address>? | off | status"},
        {NULL, NULL, 0, 0, NULL}};
    ms_cmdset_extend_quiet(app, "display", table);
}
