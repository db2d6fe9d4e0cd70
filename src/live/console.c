/* console.c: what the live page runs in the session (live.h): a command typed in its console
 * (Tcl, or Python through ::molscope::live::python) or one command given as its words (the
 * panels' `mol modstyle ...`), evaluated at the global level like a command at the prompt,
 * with what it writes to stdout and stderr captured (the descriptors sent to a temporary
 * file for the time of the command, then passed on) and answered as JSON; and the
 * session's state for the panels, read by tcl/live/live.tcl's ::molscope::live::session
 * with the catalog of drawing methods and colouring methods added from the rep module. */
#include "config.h"
#include "live/live.h"
#include "rep/rep.h"

#include <stdio.h>
#include <string.h>
#include <tcl.h>
#include <unistd.h>

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

/* What the command writes to a descriptor (Tcl's puts, the C printf of `mol list`, Python's
 * prints) goes to a temporary file for its time, then is read back and written on to the
 * real descriptor, so the terminal still gets it, after the command. */
typedef struct capture {
    int fd, saved;
    FILE *tmp;
} capture;

static void flush_fd(Tcl_Interp *interp, int fd)
{
    Tcl_Channel ch = Tcl_GetStdChannel(fd == 1 ? TCL_STDOUT : TCL_STDERR);
    if (ch) Tcl_Flush(ch);
    fflush(fd == 1 ? stdout : stderr);
}

static void capture_start(Tcl_Interp *interp, capture *c, int fd)
{
    c->fd = fd;
    c->saved = -1;
    if (!(c->tmp = tmpfile())) return;
    flush_fd(interp, fd);
    if ((c->saved = dup(fd)) < 0 || dup2(fileno(c->tmp), fd) < 0) {
        if (c->saved >= 0) close(c->saved);
        fclose(c->tmp);
        c->tmp = NULL;
    }
}

/* Put the descriptor back; what was written is appended to text (MAX_CAPTURE at most) and
 * written on to the descriptor. */
static void capture_stop(Tcl_Interp *interp, capture *c, Tcl_DString *text)
{
    if (!c->tmp) return;
    flush_fd(interp, c->fd);
    dup2(c->saved, c->fd);
    close(c->saved);
    rewind(c->tmp);
    char buf[8192];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, c->tmp)) > 0) {
        size_t keep = MAX_CAPTURE - (size_t)Tcl_DStringLength(text);
        Tcl_DStringAppend(text, buf, (int)(n < keep ? n : keep));
        for (size_t off = 0; off < n;) {
            ssize_t w = write(c->fd, buf + off, n - off);
            if (w <= 0) break;
            off += (size_t)w;
        }
    }
    fclose(c->tmp);
    c->tmp = NULL;
}

/* ---------------------------------------------------------------- running commands */

int ms_live_run(ms_app *app, Tcl_Obj *cmd, int as_words, Tcl_DString *json)
{
    Tcl_Interp *interp = app->interp;
    capture out, err;
    Tcl_DString text;
    Tcl_Obj **objv;
    int objc = 0, rc;
    Tcl_IncrRefCount(cmd);
    capture_start(interp, &out, 1);
    capture_start(interp, &err, 2);
    if (as_words && Tcl_ListObjGetElements(interp, cmd, &objc, &objv) == TCL_OK && objc > 0)
        rc = Tcl_EvalObjv(interp, objc, objv, TCL_EVAL_GLOBAL);
    else if (as_words)
        rc = objc == 0 ? (Tcl_SetResult(interp, "no command given", TCL_STATIC), TCL_ERROR) : TCL_ERROR;
    else
        rc = Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
    Tcl_DStringInit(&text);
    capture_stop(interp, &out, &text);
    capture_stop(interp, &err, &text);
    Tcl_DecrRefCount(cmd);
    Tcl_DStringAppend(json, rc == TCL_ERROR ? "{\"ok\":false," : "{\"ok\":true,", -1);
    json_key(json, rc == TCL_ERROR ? "error" : "result", Tcl_GetStringResult(interp));
    Tcl_DStringAppend(json, ",\"output\":", -1);
    ms_live_json_str(json, Tcl_DStringValue(&text), (size_t)Tcl_DStringLength(&text));
    Tcl_DStringAppend(json, "}", 1);
    Tcl_DStringFree(&text);
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
