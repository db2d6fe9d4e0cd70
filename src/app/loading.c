/* loading.c: VMD's background frame loading (`waitfor`). The frames a load leaves pending
 * are read while Tcl is idle, about 50 ms of work per turn, and to the end by `update`,
 * `vwait` and `display update`, which therefore never wait on a load that is still going.
 * A damaged frame found on the way ends that file's load: the frames read before it stay,
 * and the damage is reported at once as a Tcl background error (`interp bgerror`), which
 * Tcl's default handler prints on stderr. */
#include "config.h"
#include "app/app.h"
#include "fileio/load.h"

#include <stdio.h>
#include <stdlib.h>

#define IDLE_TURN_S 0.05   /* the longest one idle turn reads frames */

/* Whether m is still molecule `id` of the set (a trace callback may delete molecules). */
static int still_there(ms_app *app, const ms_molecule *m, int id)
{
    return ms_molset_get(&app->mols, id) == m;
}

/* Hand an error to the interpreter's background error handler now, not at the next idle
 * turn (the program may be about to end); the interpreter's result is left as it was. */
static void report_bgerror(Tcl_Interp *interp, Tcl_Obj *msg, Tcl_Obj *info, Tcl_Obj *code)
{
    Tcl_InterpState saved = Tcl_SaveInterpState(interp, TCL_OK);
    Tcl_Obj *cmd = NULL;
    int rc = TCL_ERROR;
    if (!Tcl_InterpDeleted(interp) &&
        Tcl_EvalEx(interp, "::interp bgerror {}", -1, TCL_EVAL_GLOBAL) == TCL_OK) {
        cmd = Tcl_DuplicateObj(Tcl_GetObjResult(interp));
        Tcl_IncrRefCount(cmd);
        Tcl_Obj *opts = Tcl_NewDictObj();
        Tcl_DictObjPut(NULL, opts, Tcl_NewStringObj("-code", -1), Tcl_NewIntObj(TCL_ERROR));
        Tcl_DictObjPut(NULL, opts, Tcl_NewStringObj("-level", -1), Tcl_NewIntObj(0));
        Tcl_DictObjPut(NULL, opts, Tcl_NewStringObj("-errorcode", -1), code);
        Tcl_DictObjPut(NULL, opts, Tcl_NewStringObj("-errorinfo", -1), info);
        if (Tcl_ListObjAppendElement(interp, cmd, msg) == TCL_OK &&
            Tcl_ListObjAppendElement(interp, cmd, opts) == TCL_OK)
            rc = Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
        else
            Tcl_DecrRefCount(opts);
    }
    if (rc == TCL_ERROR)
        fprintf(stderr, "molscope: the background error handler failed (%s); the error was:\n%s\n",
                cmd ? Tcl_GetStringResult(interp) : "no handler", Tcl_GetString(info));
    if (cmd) Tcl_DecrRefCount(cmd);
    Tcl_RestoreInterpState(interp, saved);
}

/* A damaged file found while reading molecule `id`'s frames in the background. */
static void report_load_error(ms_app *app, int id, const char *path, const char *what)
{
    Tcl_Obj *msg = Tcl_ObjPrintf("molecule %d: %s: %s", id, path ? path : "?", what);
    Tcl_Obj *info = Tcl_ObjPrintf("%s\n    (reading the frames of molecule %d in the background)",
                                  Tcl_GetString(msg), id);
    Tcl_Obj *code = Tcl_NewListObj(0, NULL);
    Tcl_ListObjAppendElement(NULL, code, Tcl_NewStringObj("MOLSCOPE", -1));
    Tcl_ListObjAppendElement(NULL, code, Tcl_NewStringObj("LOAD", -1));
    Tcl_ListObjAppendElement(NULL, code, Tcl_NewIntObj(id));
    Tcl_ListObjAppendElement(NULL, code, Tcl_NewStringObj(path ? path : "", -1));
    Tcl_IncrRefCount(msg);
    Tcl_IncrRefCount(info);
    Tcl_IncrRefCount(code);
    report_bgerror(app->interp, msg, info, code);
    Tcl_DecrRefCount(msg);
    Tcl_DecrRefCount(info);
    Tcl_DecrRefCount(code);
}

/* Read up to max (all when < 0) of m's pending frames, report a damaged file, then tell the
 * listeners (trace variables) about the new frames. Returns 1 when m still exists and still
 * has frames pending. */
static int pump_one(ms_app *app, ms_molecule *m, long max)
{
    if (!m->pending) return 0;
    ms_error err = {{0}};
    char *done = NULL;
    int id = m->id;
    size_t before = m->nframes;
    int rc = ms_loader_pump(m, max, &done, &err);
    if (rc < 0) report_load_error(app, id, done, err.msg);
    if (still_there(app, m, id) && m->nframes != before) {
        ms_molset_emit(&app->mols, MS_EV_FRAMES_ADDED, m, NULL);
        if (still_there(app, m, id)) ms_molset_set_frame(&app->mols, m, (long)m->nframes - 1);
    }
    if (done && rc == 0 && still_there(app, m, id))
        ms_molset_emit(&app->mols, MS_EV_TRAJ_DONE, m, done);
    free(done);
    return still_there(app, m, id) && m->pending;
}

static int any_pending(const ms_app *app)
{
    for (size_t i = 0; i < app->mols.n; i++)
        if (app->mols.mols[i]->pending) return 1;
    return 0;
}

/* One idle turn: frames one at a time until the turn's time is up (VMD reads one frame per
 * redraw), so an interactive session stays responsive. */
static void idle_load(ClientData cd)
{
    ms_app *app = cd;
    app->idle_scheduled = 0;
    double until = ms_now() + IDLE_TURN_S;
    for (size_t i = 0; i < app->mols.n && ms_now() < until; i++)
        while (ms_now() < until && i < app->mols.n && pump_one(app, app->mols.mols[i], 1)) {}
    if (any_pending(app)) ms_app_schedule_loading(app);
}

void ms_app_schedule_loading(ms_app *app)
{
    if (app->idle_scheduled) return;
    app->idle_scheduled = 1;
    Tcl_DoWhenIdle(idle_load, app);
}

void ms_app_stop_loading(ms_app *app)
{
    if (app->idle_scheduled) Tcl_CancelIdleCall(idle_load, app);
    app->idle_scheduled = 0;
}

void ms_app_finish_loading(ms_app *app)
{
    for (size_t i = 0; i < app->mols.n; i++)
        while (i < app->mols.n && pump_one(app, app->mols.mols[i], -1)) {}
}

int ms_app_finish_molecule(ms_app *app, ms_molecule *m)
{
    int id = m->id;
    while (pump_one(app, m, -1)) {}
    return still_there(app, m, id) ? 0 : -1;
}

/* ---------------------------------------------------------------- update and vwait */

/* Tcl's own update or vwait, called after the pending frames are read. */
typedef struct wrapped_cmd {
    ms_app *app;
    Tcl_CmdInfo tcl;
} wrapped_cmd;

static int cmd_finish_then(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    wrapped_cmd *w = cd;
    ms_app_finish_loading(w->app);
    return w->tcl.objProc(w->tcl.objClientData, interp, objc, objv);
}

static void wrapped_free(ClientData cd)
{
    free(cd);
}

static void wrap_command(ms_app *app, const char *name)
{
    wrapped_cmd *w = calloc(1, sizeof *w);
    if (!w) return;          /* Tcl's command stays, loads then finish at idle time */
    w->app = app;
    if (!Tcl_GetCommandInfo(app->interp, name, &w->tcl) || !w->tcl.objProc) {
        free(w);
        return;
    }
    Tcl_CreateObjCommand(app->interp, name, cmd_finish_then, w, wrapped_free);
}

void ms_app_register_loading(ms_app *app)
{
    wrap_command(app, "update");
    wrap_command(app, "vwait");
}
