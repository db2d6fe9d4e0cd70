/* console.c: what the live page runs in the session (live.h): a command typed in its console
 * (Tcl, or Python through ::molscope::live::python) or one command given as its words (the
 * panels' `mol modstyle ...`), evaluated at the global level like a command at the prompt,
 * with what it writes to stdout and stderr captured (a channel stacked over each for the
 * time of the command, which also passes everything on) and answered as JSON; and the
 * session's state for the panels, read by tcl/live/live.tcl's ::molscope::live::session
 * with the catalog of drawing methods and colouring methods added from the rep module. */
#include "config.h"
#include "live/live.h"
#include "rep/rep.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <tcl.h>

#define MAX_CAPTURE (1 << 20)        /* output kept per command; the rest is dropped */

/* ---------------------------------------------------------------- JSON */

void ms_live_json_str(Tcl_DString *out, const char *s, size_t n)
{
    Tcl_DStringAppend(out, "\"", 1);
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)s[i];
        char esc[8];
        if (ch == '"' || ch == '\\') {
            esc[0] = '\\';
            esc[1] = (char)ch;
            Tcl_DStringAppend(out, esc, 2);
        } else if (ch < 0x20) {
            snprintf(esc, sizeof esc, "\\u%04x", ch);
            Tcl_DStringAppend(out, esc, -1);
        } else {
            Tcl_DStringAppend(out, (const char *)&s[i], 1);
        }
    }
    Tcl_DStringAppend(out, "\"", 1);
}

static void json_key(Tcl_DString *out, const char *key, const char *value)
{
    Tcl_DStringAppend(out, "\"", 1);
    Tcl_DStringAppend(out, key, -1);
    Tcl_DStringAppend(out, "\":", 2);
    ms_live_json_str(out, value, strlen(value));
}

/* ---------------------------------------------------------------- output capture */

typedef struct capture {
    Tcl_Channel base;                /* the standard channel (its handle stays the bottom) */
    Tcl_Channel top;                 /* the stacked channel, NULL when none */
    Tcl_DString text;
} capture;

static int cap_close(ClientData cd, Tcl_Interp *interp)
{
    return 0;
}

static int cap_input(ClientData cd, char *buf, int n, int *err)
{
    *err = EINVAL;
    return -1;
}

static int cap_output(ClientData cd, const char *buf, int n, int *err)
{
    capture *c = cd;
    if (Tcl_DStringLength(&c->text) + n <= MAX_CAPTURE) Tcl_DStringAppend(&c->text, buf, n);
    Tcl_Channel below = c->top ? Tcl_GetStackedChannel(c->top) : NULL;
    if (below) Tcl_WriteRaw(below, buf, n);
    return n;
}

static void cap_watch(ClientData cd, int mask)
{
}

static int cap_handle(ClientData cd, int direction, ClientData *handle)
{
    return TCL_ERROR;
}

static const Tcl_ChannelType cap_type = {
    "molscope-live-capture", TCL_CHANNEL_VERSION_5, cap_close, cap_input, cap_output, NULL, NULL,
    NULL, cap_watch, cap_handle, NULL, NULL, NULL, NULL, NULL, NULL, NULL};

static void capture_start(Tcl_Interp *interp, capture *c, int which)
{
    Tcl_DStringInit(&c->text);
    c->base = Tcl_GetStdChannel(which);
    c->top = c->base ? Tcl_StackChannel(interp, &cap_type, c, TCL_WRITABLE, c->base) : NULL;
}

/* Unstack the channel when the command left it in place (it may have closed the channel or
 * set another standard channel). */
static void capture_stop(Tcl_Interp *interp, capture *c, int which)
{
    if (c->top && Tcl_GetStdChannel(which) == c->base && Tcl_GetTopChannel(c->base) == c->top) {
        Tcl_Flush(c->top);
        Tcl_UnstackChannel(interp, c->top);
    }
    c->top = NULL;
}

/* ---------------------------------------------------------------- running commands */

int ms_live_run(ms_app *app, Tcl_Obj *cmd, int as_words, Tcl_DString *json)
{
    Tcl_Interp *interp = app->interp;
    capture out, err;
    Tcl_Obj **objv;
    int objc = 0, rc;
    Tcl_IncrRefCount(cmd);
    capture_start(interp, &out, TCL_STDOUT);
    capture_start(interp, &err, TCL_STDERR);
    if (as_words && Tcl_ListObjGetElements(interp, cmd, &objc, &objv) == TCL_OK && objc > 0)
        rc = Tcl_EvalObjv(interp, objc, objv, TCL_EVAL_GLOBAL);
    else if (as_words)
        rc = objc == 0 ? (Tcl_SetResult(interp, "no command given", TCL_STATIC), TCL_ERROR) : TCL_ERROR;
    else
        rc = Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
    capture_stop(interp, &err, TCL_STDERR);
    capture_stop(interp, &out, TCL_STDOUT);
    Tcl_DecrRefCount(cmd);
    Tcl_DStringAppend(&out.text, Tcl_DStringValue(&err.text), Tcl_DStringLength(&err.text));
    Tcl_DStringAppend(json, rc == TCL_ERROR ? "{\"ok\":false," : "{\"ok\":true,", -1);
    json_key(json, rc == TCL_ERROR ? "error" : "result", Tcl_GetStringResult(interp));
    Tcl_DStringAppend(json, ",\"output\":", -1);
    ms_live_json_str(json, Tcl_DStringValue(&out.text), (size_t)Tcl_DStringLength(&out.text));
    Tcl_DStringAppend(json, "}", 1);
    Tcl_DStringFree(&out.text);
    Tcl_DStringFree(&err.text);
    Tcl_ResetResult(interp);
    return rc == TCL_ERROR ? -1 : 0;
}

/* ---------------------------------------------------------------- the session's state */

/* The drawing methods with their parameters, and the colouring methods. */
static void catalog(Tcl_DString *json)
{
    char num[64];
    Tcl_DStringAppend(json, "\"methods\":[", -1);
    for (size_t i = 0; i < ms_rep_method_count(); i++) {
        const ms_rep_method *m = ms_rep_method_at(i);
        Tcl_DStringAppend(json, i ? ",{" : "{", -1);
        json_key(json, "name", m->name);
        Tcl_DStringAppend(json, ",\"params\":[", -1);
        for (int k = 0; k < m->nparams; k++) {
            Tcl_DStringAppend(json, k ? ",{" : "{", -1);
            json_key(json, "name", m->param[k].name);
            snprintf(num, sizeof num, ",\"default\":%g}", (double)m->param[k].def);
            Tcl_DStringAppend(json, num, -1);
        }
        Tcl_DStringAppend(json, "]}", -1);
    }
    Tcl_DStringAppend(json, "],\"colorings\":[", -1);
    for (int c = 0; c < MS_COL_NMETHODS; c++) {
        const char *name = ms_rep_colmethod_name((ms_colmethod)c);
        if (c) Tcl_DStringAppend(json, ",", 1);
        ms_live_json_str(json, name, strlen(name));
    }
    Tcl_DStringAppend(json, "]", 1);
}

int ms_live_session_json(ms_app *app, int raster_only, Tcl_DString *json, ms_error *err)
{
    /* the queries change nothing, though some of their commands count as changes */
    unsigned long version = app->world.scene_version;
    Tcl_Obj *cmd = Tcl_NewStringObj("::molscope::live::session", -1);
    Tcl_IncrRefCount(cmd);
    int rc = Tcl_EvalObjEx(app->interp, cmd, TCL_EVAL_GLOBAL);
    Tcl_DecrRefCount(cmd);
    app->world.scene_version = version;
    if (rc != TCL_OK) {
        ms_error_set(err, "session: %.400s", Tcl_GetStringResult(app->interp));
        Tcl_ResetResult(app->interp);
        return -1;
    }
    char head[160];
    snprintf(head, sizeof head, "{\"version\":%lu,\"mode\":\"%s\",\"python\":%s,", version,
             raster_only ? "raster" : "progressive",
             Tcl_FindCommand(app->interp, "gopython", NULL, TCL_GLOBAL_ONLY) ? "true" : "false");
    Tcl_DStringAppend(json, head, -1);
    catalog(json);
    Tcl_DStringAppend(json, ",\"session\":", -1);
    Tcl_DStringAppend(json, Tcl_GetStringResult(app->interp), -1);
    Tcl_DStringAppend(json, "}", 1);
    Tcl_ResetResult(app->interp);
    return 0;
}
