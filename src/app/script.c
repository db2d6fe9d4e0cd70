/* script.c: reading scripts as VMD reads them. A file of commands (-e, `play`, the startup
 * file) and standard input run one complete command at a time: lines are read until the
 * text is a complete command (Tcl's info complete), the command is evaluated at the global
 * level, its result is echoed on stdout (rank 0 only) and an error is printed the same way,
 * with its stack trace on stderr; then the next command runs. Only `source` (plain Tcl)
 * stops at its first error. Failed commands are counted so that a batch run can end with a
 * summary and a non-zero status (the one difference from VMD, which always exits 0).
 *
 * Under several MPI ranks a failed command stops the run instead: a rank going on alone
 * would wait for ever in the next collective call of the others.
 *
 * The command log (`logfile`) is written here too: every command read this way is recorded
 * as typed, before it runs, straight into the file (base/safewrite's log: no buffer, no
 * temporary file), so a script that dies halfway leaves the log of what it ran. */
#include "config.h"
#include "app/app.h"
#include "base/safewrite.h"
#include "parallel/parallel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---------------------------------------------------------------- the command log */

static void log_write(ms_app *app, const char *text, size_t n)
{
    ms_error err = {{0}};
    if (app->log_console) {
        fwrite(text, 1, n, stdout);
        fflush(stdout);
    } else if (app->log && (ms_ofile_write(app->log, text, n, &err) || ms_ofile_check(app->log, &err))) {
        fprintf(stderr, "molscope: logfile: %s; logging stopped\n", err.msg);
        ms_ofile_abort(app->log);
        app->log = NULL;
    }
}

int ms_app_log_close(ms_app *app, ms_error *err)
{
    app->log_console = 0;
    if (!app->log) return 0;
    ms_ofile *o = app->log;
    app->log = NULL;
    return ms_ofile_commit(o, err);
}

int ms_app_log_open(ms_app *app, const char *path, ms_error *err)
{
    ms_ofile *o = NULL;
    if (path && !(o = ms_ofile_open_log(path, err))) return -1;
    if (ms_app_log_close(app, err)) {
        ms_ofile_abort(o);
        return -1;
    }
    app->log = o;
    app->log_console = path == NULL;
    char head[512];
    time_t now = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%a %b %d %H:%M:%S %Y", localtime(&now));
    int n = snprintf(head, sizeof head, "# molscope %s (VMD-compatible command log)\n"
                     "# Log file '%s', created %s\n", PACKAGE_VERSION, path ? path : "console",
                     when);
    log_write(app, head, (size_t)n);
    return 0;
}

/* Record a command as typed (with its newline), and in vmd_logfile as VMD does. */
static void log_command(ms_app *app, Tcl_Obj *cmd)
{
    if (!app->log && !app->log_console) return;
    int n;
    const char *s = Tcl_GetStringFromObj(cmd, &n);
    while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == ' ' || s[n - 1] == '\t')) n--;
    if (n == 0) return;
    log_write(app, s, (size_t)n);
    log_write(app, "\n", 1);
    Tcl_SetVar2Ex(app->interp, "vmd_logfile", NULL, Tcl_NewStringObj(s, n), TCL_GLOBAL_ONLY);
}

/* ---------------------------------------------------------------- failures */

void ms_app_note_failure(ms_app *app, const char *where, int line)
{
    Tcl_Interp *interp = app->interp;
    /* hold the result: reading errorInfo may replace it */
    Tcl_Obj *res = Tcl_GetObjResult(interp);
    Tcl_IncrRefCount(res);
    const char *msg = Tcl_GetString(res);
    const char *info = Tcl_GetVar(interp, "errorInfo", TCL_GLOBAL_ONLY);
    size_t mlen = strlen(msg);
    /* VMD prints the message as the command's result, on stdout */
    if (ms_par_rank() == 0 && *msg) printf("%s\n", msg);
    fflush(stdout);
    /* then where it happened and the stack trace, which errorInfo has after the message */
    const char *trace = info && strncmp(info, msg, mlen) == 0 ? info + mlen : info ? info : "";
    while (*trace == '\n') trace++;
    char place[300];
    if (line > 0) snprintf(place, sizeof place, "%s line %d", where ? where : "?", line);
    else snprintf(place, sizeof place, "%s", where ? where : "?");
    fprintf(stderr, "molscope: %s: %s\n", place, msg);
    if (*trace) fprintf(stderr, "%s\n", trace);
    fflush(stderr);
    if (app->failed++ == 0) {
        snprintf(app->first_failure, sizeof app->first_failure, "%s: %.600s", place, msg);
        char *nl = strchr(app->first_failure, '\n');
        if (nl) *nl = '\0';
    }
    Tcl_SetObjResult(interp, res);
    Tcl_DecrRefCount(res);
}

int ms_app_exit_status(ms_app *app, int status)
{
    if (app->interactive || app->failed == 0) return status;
    if (ms_par_rank() == 0)
        fprintf(stderr, "molscope: %d command%s failed; the first: %s\n", app->failed,
                app->failed == 1 ? "" : "s", app->first_failure);
    return status ? status : 1;
}

/* ---------------------------------------------------------------- one command */

int ms_app_run_command(ms_app *app, Tcl_Obj *cmd, const char *where, int line)
{
    log_command(app, cmd);
    int rc = Tcl_EvalObjEx(app->interp, cmd, TCL_EVAL_GLOBAL);
    if (app->quit_requested) return TCL_OK;
    if (rc == TCL_OK) {
        const char *res = Tcl_GetStringResult(app->interp);
        if (*res && ms_par_rank() == 0) printf("%s\n", res);
        fflush(stdout);
        return TCL_OK;
    }
    ms_app_note_failure(app, where, line);
    return TCL_ERROR;
}

int ms_app_stop_on_error(void)
{
    return ms_par_size() > 1;
}

/* ---------------------------------------------------------------- a file of commands */

/* Evaluate the commands of an open channel; returns TCL_ERROR only when a failure must stop
 * the run (several ranks). */
static int play_channel(ms_app *app, Tcl_Channel in, const char *path)
{
    Tcl_Obj *pending = NULL, *line = Tcl_NewObj();
    Tcl_IncrRefCount(line);
    int lineno = 0, first = 0, rc = TCL_OK;
    while (rc == TCL_OK && !app->quit_requested) {
        Tcl_SetObjLength(line, 0);
        if (Tcl_GetsObj(in, line) < 0) break;
        lineno++;
        if (!pending) {
            pending = Tcl_NewObj();
            Tcl_IncrRefCount(pending);
            first = lineno;
        }
        Tcl_AppendObjToObj(pending, line);
        Tcl_AppendToObj(pending, "\n", 1);
        if (!Tcl_CommandComplete(Tcl_GetString(pending))) continue;
        Tcl_Obj *cmd = pending;
        pending = NULL;
        if (ms_app_run_command(app, cmd, path, first) != TCL_OK && ms_app_stop_on_error())
            rc = TCL_ERROR;
        Tcl_DecrRefCount(cmd);
    }
    if (pending && rc == TCL_OK && !app->quit_requested) {
        Tcl_SetObjResult(app->interp, Tcl_ObjPrintf("the file ends inside an unfinished command "
                                                    "(missing close-brace or quote)"));
        Tcl_SetVar(app->interp, "errorInfo", "", TCL_GLOBAL_ONLY);
        ms_app_note_failure(app, path, first);
        if (ms_app_stop_on_error()) rc = TCL_ERROR;
    }
    if (pending) Tcl_DecrRefCount(pending);
    Tcl_DecrRefCount(line);
    return rc;
}

/* Set what [info script] answers; returns the name it answered before (a new reference). */
static Tcl_Obj *swap_info_script(Tcl_Interp *interp, Tcl_Obj *name)
{
    Tcl_EvalEx(interp, "info script", -1, TCL_EVAL_GLOBAL);
    Tcl_Obj *old = Tcl_GetObjResult(interp);
    Tcl_IncrRefCount(old);
    Tcl_Obj *cmd = Tcl_NewListObj(0, NULL);
    Tcl_IncrRefCount(cmd);
    Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("info", -1));
    Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("script", -1));
    Tcl_ListObjAppendElement(NULL, cmd, name);
    Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
    Tcl_DecrRefCount(cmd);
    return old;
}

int ms_app_play(ms_app *app, const char *path)
{
    Tcl_Interp *interp = app->interp;
    Tcl_Channel in = Tcl_OpenFileChannel(interp, path, "r", 0);
    if (!in) {
        Tcl_SetObjResult(interp, Tcl_ObjPrintf("cannot open '%s': %s", path, Tcl_PosixError(interp)));
        return TCL_ERROR;
    }
    Tcl_Obj *outer = swap_info_script(interp, Tcl_NewStringObj(path, -1));
    int rc = play_channel(app, in, path);
    Tcl_Obj *err = Tcl_GetObjResult(interp);
    Tcl_IncrRefCount(err);
    Tcl_DecrRefCount(swap_info_script(interp, outer));
    Tcl_DecrRefCount(outer);
    Tcl_Close(NULL, in);
    if (rc == TCL_OK) Tcl_ResetResult(interp);
    else Tcl_SetObjResult(interp, err);
    Tcl_DecrRefCount(err);
    return rc;
}
