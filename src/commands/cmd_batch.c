/* cmd_batch.c: VMD's commands for running scripts and talking to the console:
 *
 *   play <file>                       run a file of commands as -e does (app/script.c): one
 *                                     complete command at a time, an error printed and the
 *                                     next command run
 *   logfile <file>|console|off        record every command read from a script or standard
 *                                     input, as typed (and in vmd_logfile)
 *   vmdcon ?-info|-warn|-err|-all? ?-nonewline? <text>
 *                                     print a console message ("Info) ...", "Warning) ...",
 *                                     "ERROR) ..."), below -loglevel silenced
 *   vmdcon -loglevel ?all|info|warn|err|none?;  vmdcon -status;  vmdcon -dmesg
 *   sleep <seconds>                   do nothing for that long
 *   wait <seconds>                    let the event loop (background loads) run that long
 *                                     before the next command */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"

#include <stdio.h>
#include <string.h>

#define MAX_WAIT_S 1e6

/* ---------------------------------------------------------------- play and logfile */

static int cmd_play(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    if (ms_app_play(app, Tcl_GetString(objv[1])) != TCL_OK)
        return ms_cmd_error(interp, "play: %s", Tcl_GetStringResult(interp));
    return TCL_OK;
}

static int cmd_logfile(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    const char *what = Tcl_GetString(objv[1]);
    ms_error err = {{0}};
    int rc = ms_word_eq(what, "off")       ? ms_app_log_close(app, &err)
             : ms_word_eq(what, "console") ? ms_app_log_open(app, NULL, &err)
                                           : ms_app_log_open(app, what, &err);
    if (rc) return ms_cmd_error(interp, "logfile: %s", err.msg);
    return TCL_OK;
}

/* ---------------------------------------------------------------- vmdcon */

enum { LVL_ALL, LVL_INFO, LVL_WARN, LVL_ERR, LVL_ALWAYS, LVL_NONE };
static const char *const level_names[] = {"all", "info", "warn", "err", "always", "none", NULL};
static const char *const level_prefix[] = {"", "Info) ", "Warning) ", "ERROR) ", "", ""};
#define DMESG_MAX 2000

/* Keep every message for vmdcon -dmesg, the last DMESG_MAX of them. */
static void dmesg_keep(Tcl_Interp *interp, Tcl_Obj *text)
{
    Tcl_Obj *log = Tcl_GetVar2Ex(interp, "::molscope::dmesg", NULL, TCL_GLOBAL_ONLY);
    log = log ? (Tcl_IsShared(log) ? Tcl_DuplicateObj(log) : log) : Tcl_NewListObj(0, NULL);
    Tcl_ListObjAppendElement(NULL, log, text);
    int n = 0;
    Tcl_ListObjLength(NULL, log, &n);
    if (n > DMESG_MAX) Tcl_ListObjReplace(NULL, log, 0, n - DMESG_MAX, 0, NULL);
    Tcl_SetVar2Ex(interp, "::molscope::dmesg", NULL, log, TCL_GLOBAL_ONLY);
}

static int vmdcon_loglevel(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int i)
{
    if (i + 1 < objc) {
        int lvl;
        if (ms_arg_choice(interp, objv[i + 1], level_names, "log level", &lvl)) return TCL_ERROR;
        app->con_loglevel = lvl == LVL_ALWAYS ? LVL_ALL : lvl;
        return TCL_OK;
    }
    Tcl_SetObjResult(interp, Tcl_NewStringObj(level_names[app->con_loglevel], -1));
    return TCL_OK;
}

static int vmdcon_dmesg(Tcl_Interp *interp)
{
    Tcl_Obj *log = Tcl_GetVar2Ex(interp, "::molscope::dmesg", NULL, TCL_GLOBAL_ONLY);
    Tcl_Obj **v;
    int n = 0;
    if (log && Tcl_ListObjGetElements(NULL, log, &n, &v) == TCL_OK)
        for (int k = 0; k < n; k++) fputs(Tcl_GetString(v[k]), stdout);
    fflush(stdout);
    return TCL_OK;
}

static int cmd_vmdcon(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const opts[] = {"-info", "-warn", "-err", "-all", "-nonewline",
                                       "-loglevel", "-status", "-dmesg", "-register",
                                       "-unregister", "-textmode", "-widgetmode", NULL};
    int level = LVL_ALWAYS, newline = 1, i = 1;
    for (; i < objc; i++) {
        int k = ms_args_find(opts, sizeof *opts, Tcl_GetString(objv[i]));
        if (k < 0) break;
        if (k <= 3) level = k == 3 ? LVL_ALWAYS : k + 1;
        else if (k == 4) newline = 0;
        else if (k == 5) return vmdcon_loglevel(app, interp, objc, objv, i);
        else if (k == 6) return Tcl_SetObjResult(interp, Tcl_NewStringObj("text", -1)), TCL_OK;
        else if (k == 7) return vmdcon_dmesg(interp);
        else return TCL_OK;   /* console widgets: there is none without a display */
    }
    if (i != objc - 1) return ms_args_usage(interp);
    Tcl_Obj *text = Tcl_ObjPrintf("%s%s%s", level_prefix[level], Tcl_GetString(objv[i]),
                                  newline ? "\n" : "");
    Tcl_IncrRefCount(text);
    if (level >= app->con_loglevel) {
        fputs(Tcl_GetString(text), stdout);
        fflush(stdout);
    }
    dmesg_keep(interp, text);
    Tcl_DecrRefCount(text);
    return TCL_OK;
}

/* ---------------------------------------------------------------- sleep and wait */

static int read_seconds(Tcl_Interp *interp, Tcl_Obj *word, double *s)
{
    return ms_arg_double_range(interp, word, "seconds", 0, MAX_WAIT_S, s);
}

static int cmd_sleep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    double s;
    if (read_seconds(interp, objv[1], &s)) return TCL_ERROR;
    Tcl_Sleep((int)(s * 1000 + 0.5));
    return TCL_OK;
}

static void wait_done(ClientData cd)
{
    *(int *)cd = 1;
}

static int cmd_wait(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    double s;
    if (read_seconds(interp, objv[1], &s)) return TCL_ERROR;
    int done = 0;
    Tcl_TimerToken t = Tcl_CreateTimerHandler((int)(s * 1000 + 0.5), wait_done, &done);
    while (!done && !app->quit_requested) Tcl_DoOneEvent(TCL_ALL_EVENTS);
    Tcl_DeleteTimerHandler(t);
    return TCL_OK;
}

void ms_cmd_batch_register(ms_app *app)
{
    static const ms_subcmd cmds[] = {
        {"play", cmd_play, 1, 1, "<file>"},
        {"logfile", cmd_logfile, 1, 1, "<file>|console|off"},
        {"vmdcon", cmd_vmdcon, 1, MS_ARGS_ANY,
         "?-info|-warn|-err|-all? ?-nonewline? <text> | -loglevel ?<level>? | -status | -dmesg"},
        {"sleep", cmd_sleep, 1, 1, "<seconds>"},
        {"wait", cmd_wait, 1, 1, "<seconds>"}};
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
