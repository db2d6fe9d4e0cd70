/* shell.c: the read-evaluate loop. Interactive when stdin is a terminal (line editing and
 * history through tclreadline when it is installed, loaded at run time; a plain prompt
 * otherwise); batch otherwise. Either way standard input is read as VMD reads it (script.c):
 * one complete command at a time, results echoed, an error printed and the next command
 * run; a batch run counts the failures for its exit status. Tcl events (background frame
 * loading, servers) run while the shell waits for input; while a command runs, standard
 * input is not watched, so a command that runs the event loop itself (update, vwait) sees
 * only the other events.
 *
 * Under MPI only rank 0 has standard input: it reads each line and broadcasts it, and every
 * rank evaluates it, so `mpirun -np 4 molscope < script.tcl` runs the script on every rank.
 * Only rank 0 echoes results (the informational output); `puts` prints on every rank. With
 * several ranks an error ends the job (a rank going on alone would hang the others). */
#include "config.h"
#include "app/shell.h"
#include "parallel/parallel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PROMPT "molscope > "

typedef struct shell {
    ms_app *app;
    Tcl_Obj *pending;   /* lines of an incomplete command */
    int done;           /* EOF reached */
    int status;         /* exit status */
    int line, first;    /* lines read; the line the pending command starts on */
} shell;

void ms_shell_report_error(ms_app *app, const char *context)
{
    Tcl_Interp *interp = app->interp;
    const char *info = Tcl_GetVar(interp, "errorInfo", TCL_GLOBAL_ONLY);
    const char *msg = Tcl_GetStringResult(interp);
    if (context) fprintf(stderr, "%s: ", context);
    /* errorInfo starts with the message and goes on with the Tcl stack trace. */
    fprintf(stderr, "%s\n", info && *info ? info : msg);
    fflush(stderr);
}

/* Evaluate one complete command; returns 0 to go on, 1 to stop. */
static int shell_eval(shell *sh, Tcl_Obj *cmd)
{
    ms_app *app = sh->app;
    int rc = ms_app_run_command(app, cmd, "standard input", sh->first);
    if (app->quit_requested) {
        sh->status = app->quit_status;
        return 1;
    }
    if (rc != TCL_OK && ms_app_stop_on_error()) {
        sh->status = 1;
        return 1;
    }
    return 0;
}

/* Standard input ended inside an unfinished command: an error, as in a script file. */
static void shell_unfinished(shell *sh)
{
    Tcl_SetObjResult(sh->app->interp, Tcl_NewStringObj("standard input ended inside an "
                                                       "unfinished command", -1));
    Tcl_SetVar(sh->app->interp, "errorInfo", "", TCL_GLOBAL_ONLY);
    ms_app_note_failure(sh->app, "standard input", sh->first);
    if (ms_app_stop_on_error()) sh->status = 1;
}

/* Add a line; evaluate when the command is complete. Returns 1 to stop. */
static int shell_line(shell *sh, const char *line, int len)
{
    sh->line++;
    if (!sh->pending) {
        sh->pending = Tcl_NewObj();
        Tcl_IncrRefCount(sh->pending);
        sh->first = sh->line;
    }
    Tcl_AppendToObj(sh->pending, line, len);
    Tcl_AppendToObj(sh->pending, "\n", 1);
    if (!Tcl_CommandComplete(Tcl_GetString(sh->pending))) return 0;
    Tcl_Obj *cmd = sh->pending;
    sh->pending = NULL;
    int stop = shell_eval(sh, cmd);
    Tcl_DecrRefCount(cmd);
    return stop;
}

static void prompt(shell *sh)
{
    if (!sh->app->interactive) return;
    fputs(sh->pending ? "? " : PROMPT, stdout);
    fflush(stdout);
}

static void on_stdin(ClientData cd, int mask)
{
    shell *sh = cd;
    Tcl_Channel in = Tcl_GetStdChannel(TCL_STDIN);
    Tcl_Obj *line = Tcl_NewObj();
    Tcl_IncrRefCount(line);
    int n = Tcl_GetsObj(in, line);
    if (n < 0) {
        if (Tcl_Eof(in) || !Tcl_InputBlocked(in)) {
            sh->done = 1;
            if (sh->pending && sh->app->interactive == 0) shell_unfinished(sh);
        }
        Tcl_DecrRefCount(line);
        return;
    }
    int len;
    const char *s = Tcl_GetStringFromObj(line, &len);
    /* No reading while the line runs: a command that runs the event loop (update, vwait)
     * must not have the next lines evaluated inside it, nor spin on a readable end of file
     * (where Tcl's idle work, background loading among it, would never run). */
    Tcl_DeleteChannelHandler(in, on_stdin, sh);
    if (shell_line(sh, s, len)) sh->done = 1;
    Tcl_DecrRefCount(line);
    if (sh->done) return;
    Tcl_CreateChannelHandler(in, TCL_READABLE, on_stdin, sh);
    prompt(sh);
}

/* The loop through tclreadline: returns 0 when tclreadline is not available. */
static int readline_loop(shell *sh)
{
    Tcl_Interp *interp = sh->app->interp;
    if (getenv("MOLSCOPE_NOREADLINE") ||
        Tcl_Eval(interp, "package require tclreadline") != TCL_OK)
        return 0;
    Tcl_Eval(interp, "::tclreadline::readline initialize [file join $::env(HOME) "
                     ".molscope_history]; ::tclreadline::readline eofchar "
                     "{set ::molscope::eof 1; return {}}; namespace eval ::molscope {set eof 0}");
    while (!sh->done) {
        const char *p = sh->pending ? "? " : PROMPT;
        Tcl_Obj *cmd = Tcl_ObjPrintf("::tclreadline::readline read {%s}", p);
        Tcl_IncrRefCount(cmd);
        int rc = Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
        Tcl_DecrRefCount(cmd);
        const char *eof = Tcl_GetVar(interp, "::molscope::eof", TCL_GLOBAL_ONLY);
        if (rc != TCL_OK || (eof && strcmp(eof, "1") == 0)) {
            if (sh->app->quit_requested) sh->status = sh->app->quit_status;
            putchar('\n');
            break;
        }
        Tcl_Obj *line = Tcl_GetObjResult(interp);
        Tcl_IncrRefCount(line);
        int len;
        const char *s = Tcl_GetStringFromObj(line, &len);
        char *copy = malloc((size_t)len + 1);
        if (copy) {
            memcpy(copy, s, (size_t)len + 1);
            if (shell_line(sh, copy, len)) sh->done = 1;
            free(copy);
        }
        Tcl_DecrRefCount(line);
    }
    return 1;
}

/* Several ranks: rank 0 reads a line, every rank gets it (length -1: end of input). */
static int bcast_line(Tcl_Channel in, Tcl_Obj *line, char **text, int64_t *len)
{
    ms_error err = {{0}};
    *len = -1;
    *text = NULL;
    if (ms_par_rank() == 0 && in && Tcl_GetsObj(in, line) >= 0) {
        int n;
        *text = Tcl_GetStringFromObj(line, &n);
        *len = n;
    }
    if (ms_par_bcast_small(len, sizeof *len, &err)) return -1;
    if (*len < 0) return 0;
    if (ms_par_rank() != 0 && !(*text = malloc((size_t)*len + 1)))
        ms_par_abort(1, "out of memory reading a line of %lld bytes", (long long)*len);
    ms_par_bcast(*text, (size_t)*len, &err);
    (*text)[*len] = '\0';
    return 0;
}

static int bcast_loop(shell *sh)
{
    Tcl_Channel in = Tcl_GetStdChannel(TCL_STDIN);
    while (!sh->done) {
        Tcl_Obj *line = Tcl_NewObj();
        Tcl_IncrRefCount(line);
        char *text;
        int64_t len;
        if (bcast_line(in, line, &text, &len) == 0 && len >= 0) {
            if (shell_line(sh, text, (int)len)) sh->done = 1;
        } else {
            sh->done = 1;
            if (sh->pending) shell_unfinished(sh);
        }
        if (ms_par_rank() != 0) free(text);
        Tcl_DecrRefCount(line);
        while (!sh->done && Tcl_DoOneEvent(TCL_ALL_EVENTS | TCL_DONT_WAIT)) {}
    }
    if (sh->app->quit_requested) sh->status = sh->app->quit_status;
    if (sh->pending) Tcl_DecrRefCount(sh->pending);
    return sh->status;
}

int ms_shell_run(ms_app *app)
{
    shell sh = {.app = app};
    if (ms_par_size() > 1) return bcast_loop(&sh);
    if (app->interactive && readline_loop(&sh)) {
        if (sh.pending) Tcl_DecrRefCount(sh.pending);
        return sh.status;
    }
    Tcl_Channel in = Tcl_GetStdChannel(TCL_STDIN);
    if (!in) return 0;
    Tcl_CreateChannelHandler(in, TCL_READABLE, on_stdin, &sh);
    prompt(&sh);
    while (!sh.done && !app->quit_requested) Tcl_DoOneEvent(TCL_ALL_EVENTS);
    Tcl_DeleteChannelHandler(in, on_stdin, &sh);   /* harmless when already gone */
    if (app->quit_requested) sh.status = app->quit_status;
    if (sh.pending) Tcl_DecrRefCount(sh.pending);
    if (app->interactive && !app->quit_requested) putchar('\n');
    return sh.status;
}
