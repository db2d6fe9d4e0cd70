/* atomsel.c: the `atomselect` command and the life of selection objects.
 *
 *   atomselect <molid|top> <text> ?frame <n|first|last|now>?   -> atomselectN
 *   atomselect list | keywords | symboltable
 *   atomselect macro ?name ?text??  |  atomselect delmacro name
 *   upproc level name        (VMD's helper: tie a command to another stack frame)
 *
 * Each selection is a Tcl command atomselectN (N counts up for the whole session). As in VMD
 * it is local to the proc that made it: a variable upproc_var_atomselectN is set in that
 * proc's frame with an unset trace, so returning from the proc deletes the command;
 * `$sel global` and `$sel uplevel L` move the variable. The object's methods are in
 * atomsel_getset.c and atomsel_methods.c. */
#include "config.h"
#include "commands/atomsel_int.h"
#include "commands/commands.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define TIE_PREFIX "upproc_var_"

typedef struct atomsel_state {
    ms_app *app;
    long counter;
} atomsel_state;

static int atomsel_obj_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);

int ms_atomsel_error(Tcl_Interp *interp, const ms_atomsel *s, const char *method,
                     const char *fmt, ...)
{
    char buf[1536];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return ms_cmd_error(interp, "%s %s: %s", s->name, method, buf);
}

/* ---------------------------------------------------------------- lifetime */

static char *untie_trace(ClientData cd, Tcl_Interp *interp, const char *name1,
                         const char *name2, int flags)
{
    size_t n = strlen(TIE_PREFIX);
    if ((flags & TCL_INTERP_DESTROYED) || strncmp(name1, TIE_PREFIX, n)) return NULL;
    Tcl_DeleteCommand(interp, name1 + n);
    return NULL;
}

int ms_atomsel_tie(Tcl_Interp *interp, const char *name)
{
    Tcl_Obj *var = Tcl_ObjPrintf(TIE_PREFIX "%s", name);
    Tcl_IncrRefCount(var);
    int rc = TCL_ERROR;
    if (Tcl_ObjSetVar2(interp, var, NULL, Tcl_NewIntObj(1), TCL_LEAVE_ERR_MSG))
        rc = Tcl_TraceVar(interp, Tcl_GetString(var), TCL_TRACE_UNSETS, untie_trace, NULL);
    Tcl_DecrRefCount(var);
    return rc;
}

void ms_atomsel_untie(Tcl_Interp *interp, const char *name)
{
    char var[128];
    snprintf(var, sizeof var, TIE_PREFIX "%s", name);
    Tcl_UntraceVar(interp, var, TCL_TRACE_UNSETS, untie_trace, NULL);
}

/* ::molscope::upproc_tie name: tie name to the frame this runs in (via uplevel). */
static int cmd_tie(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    return ms_atomsel_tie(interp, Tcl_GetString(objv[1]));
}

int ms_atomsel_retie(Tcl_Interp *interp, Tcl_Obj *level, const char *name)
{
    ms_atomsel_untie(interp, name);
    Tcl_Obj *script = Tcl_NewListObj(0, NULL);
    Tcl_ListObjAppendElement(NULL, script, Tcl_NewStringObj("::molscope::upproc_tie", -1));
    Tcl_ListObjAppendElement(NULL, script, Tcl_NewStringObj(name, -1));
    Tcl_Obj *words[3] = {Tcl_NewStringObj("uplevel", -1), level, script};
    for (int i = 0; i < 3; i++) Tcl_IncrRefCount(words[i]);
    int rc = Tcl_EvalObjv(interp, 3, words, 0);
    for (int i = 0; i < 3; i++) Tcl_DecrRefCount(words[i]);
    if (rc != TCL_OK) {   /* a bad level: keep the tie where it was */
        Tcl_Obj *msg = Tcl_GetObjResult(interp);
        Tcl_IncrRefCount(msg);
        ms_atomsel_tie(interp, name);
        Tcl_SetObjResult(interp, msg);
        Tcl_DecrRefCount(msg);
    }
    return rc;
}

/* upproc level name: VMD's helper, for scripts that call it themselves. */
static int cmd_upproc(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    return ms_atomsel_retie(interp, objv[1], Tcl_GetString(objv[2]));
}

/* ---------------------------------------------------------------- objects */

static void atomsel_free(ClientData cd)
{
    ms_atomsel *s = cd;
    ms_sel_free(s->expr);
    ms_bitset_free(&s->bits);
    free(s->indices);
    free(s);
}

int ms_atomsel_update(ms_app *app, ms_atomsel *s, ms_error *err)
{
    ms_molecule *m = ms_molset_get(&app->mols, s->molid);
    if (!m) {
        ms_error_set(err, "molecule %d was deleted", s->molid);
        return -1;
    }
    ms_bitset bits;
    if (ms_sel_eval(s->expr, m, s->frame, &bits, err)) return -1;
    size_t count = ms_bitset_count(&bits);
    uint32_t *idx = ms_alloc_array(count, sizeof *idx);
    if (!idx) {
        ms_bitset_free(&bits);
        ms_error_set(err, "out of memory for %zu selected atoms", count);
        return -1;
    }
    ms_bitset_indices(&bits, idx);
    ms_bitset_free(&s->bits);
    free(s->indices);
    s->bits = bits;
    s->indices = idx;
    s->count = count;
    return 0;
}

ms_molecule *ms_atomsel_fresh(ms_app *app, Tcl_Interp *interp, ms_atomsel *s,
                              const char *method)
{
    ms_molecule *m = ms_molset_get(&app->mols, s->molid);
    if (!m) {
        ms_atomsel_error(interp, s, method, "molecule %d was deleted", s->molid);
        return NULL;
    }
    if (s->bits.nbits != m->atoms.n) {   /* atoms were added since: evaluate again */
        ms_error err = {{0}};
        if (ms_atomsel_update(app, s, &err)) {
            ms_atomsel_error(interp, s, method, "%s", err.msg);
            return NULL;
        }
    }
    return m;
}

ms_atomsel *ms_atomsel_lookup(ms_app *app, Tcl_Interp *interp, const char *name,
                              const char *cmd)
{
    Tcl_CmdInfo info;
    if (Tcl_GetCommandInfo(interp, name, &info) && info.objProc == atomsel_obj_cmd) {
        ms_atomsel *s = info.objClientData;
        ms_molecule *m = ms_molset_get(&app->mols, s->molid);
        if (m && s->bits.nbits != m->atoms.n) {   /* atoms added since: evaluate again */
            ms_error err = {{0}};
            if (ms_atomsel_update(app, s, &err)) {
                ms_cmd_error(interp, "%s: %s: %s", cmd, name, err.msg);
                return NULL;
            }
        }
        if (m) return s;
        ms_cmd_error(interp, "%s: no atom selection named '%s' (its molecule %d was deleted)",
                     cmd, name, s->molid);
        return NULL;
    }
    ms_cmd_error(interp, "%s: no atom selection named '%s'", cmd, name);
    return NULL;
}

ms_molecule *ms_atomsel_mol(ms_app *app, const ms_atomsel *s)
{
    return ms_molset_get(&app->mols, s->molid);
}

long ms_atomsel_frame(ms_app *app, const ms_atomsel *s)
{
    ms_molecule *m = ms_atomsel_mol(app, s);
    return m ? ms_sel_resolve_frame(m, s->frame) : -1;
}

int ms_atomsel_parse_frame(Tcl_Interp *interp, Tcl_Obj *word, long *frame)
{
    static const char *const words[] = {"now", "last", "first", NULL};
    static const long word_frames[] = {MS_ATOMSEL_NOW, MS_ATOMSEL_LAST, 0};
    int k;
    if (ms_arg_long_or(interp, word, "frame", words, 0, 2147483647L, &k, frame)) return TCL_ERROR;
    if (k >= 0) *frame = word_frames[k];
    return TCL_OK;
}

/* ---------------------------------------------------------------- atomselect <mol> <text> */

static int atomsel_create(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const frame_word[] = {"frame", NULL};
    atomsel_state *st = Tcl_GetAssocData(interp, "ms_atomsel", NULL);
    long frame = MS_ATOMSEL_NOW;
    int k;
    if (objc == 4) return ms_args_usage(interp);
    if (objc == 5 && (ms_arg_choice(interp, objv[3], frame_word, NULL, &k) ||
                      ms_atomsel_parse_frame(interp, objv[4], &frame)))
        return TCL_ERROR;
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "atomselect");
    if (!m) return TCL_ERROR;
    ms_error err = {{0}};
    ms_atomsel *s = calloc(1, sizeof *s);
    if (!s) return ms_cmd_error(interp, "atomselect: out of memory");
    s->molid = m->id;
    s->frame = frame;
    if (!(s->expr = ms_sel_compile(Tcl_GetString(objv[2]), &err)) ||
        ms_atomsel_update(app, s, &err)) {
        atomsel_free(s);
        return ms_cmd_error(interp, "atomselect: %s", err.msg);
    }
    snprintf(s->name, sizeof s->name, "atomselect%ld", st->counter++);
    Tcl_CreateObjCommand(interp, s->name, atomsel_obj_cmd, s, atomsel_free);
    if (ms_atomsel_tie(interp, s->name) != TCL_OK) {
        Tcl_DeleteCommand(interp, s->name);
        return TCL_ERROR;
    }
    Tcl_SetObjResult(interp, Tcl_NewStringObj(s->name, -1));
    return TCL_OK;
}

/* ---------------------------------------------------------------- atomselect list/keywords */

static int list_selections(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (Tcl_Eval(interp, "lsort -dictionary [info commands {atomselect[0-9]*}]") != TCL_OK)
        return TCL_ERROR;
    Tcl_Obj *all = Tcl_GetObjResult(interp), **names, *out = Tcl_NewListObj(0, NULL);
    int n;
    Tcl_IncrRefCount(all);
    Tcl_ListObjGetElements(NULL, all, &n, &names);
    for (int i = 0; i < n; i++) {
        Tcl_CmdInfo info;
        if (Tcl_GetCommandInfo(interp, Tcl_GetString(names[i]), &info) &&
            info.objProc == atomsel_obj_cmd)
            Tcl_ListObjAppendElement(NULL, out, names[i]);
    }
    Tcl_DecrRefCount(all);
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

static void append_macro_name(void *ud, const char *name, const char *text)
{
    Tcl_ListObjAppendElement(NULL, ud, Tcl_NewStringObj(name, -1));
}

static void append_macro_symbol(void *ud, const char *name, const char *text)
{
    Tcl_Obj *e = Tcl_NewListObj(0, NULL);
    const char *w[4] = {name, name, "int", "boolean"};
    for (int i = 0; i < 4; i++) Tcl_ListObjAppendElement(NULL, e, Tcl_NewStringObj(w[i], -1));
    Tcl_ListObjAppendElement(NULL, ud, e);
}

/* keywords: every name; symboltable: {name name int|float|string keyword|boolean|...}. */
static int list_keywords(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int symbols = ms_word_eq(Tcl_GetString(objv[1]), "symboltable");
    static const char *is[] = {"int", "float", "string", "int", "float", "string"};
    static const char *takes[] = {"keyword", "keyword", "keyword", "boolean", "function",
                                  "sfunction"};
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < ms_sel_keyword_count(); i++) {
        const ms_selkw *k = ms_sel_keyword_at(i);
        const char *nm = ms_sel_keyword_name(k);
        if (!symbols) {
            Tcl_ListObjAppendElement(NULL, out, Tcl_NewStringObj(nm, -1));
            continue;
        }
        ms_selkw_type t = ms_sel_keyword_type(k);
        Tcl_Obj *e = Tcl_NewListObj(0, NULL);
        const char *w[4] = {nm, nm, is[t], takes[t]};
        for (int j = 0; j < 4; j++) Tcl_ListObjAppendElement(NULL, e, Tcl_NewStringObj(w[j], -1));
        Tcl_ListObjAppendElement(NULL, out, e);
    }
    ms_sel_macro_foreach(symbols ? append_macro_symbol : append_macro_name, out);
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

static int macro_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_error err = {{0}};
    if (objc == 2) {
        Tcl_Obj *out = Tcl_NewListObj(0, NULL);
        ms_sel_macro_foreach(append_macro_name, out);
        Tcl_SetObjResult(interp, out);
        return TCL_OK;
    }
    const char *name = Tcl_GetString(objv[2]);
    if (objc == 3) {
        long len = ms_sel_macro_get(name, NULL, 0);
        char *buf = len >= 0 ? malloc((size_t)len + 1) : NULL;
        if (len < 0) return ms_cmd_error(interp, "atomselect macro: no macro named '%s'", name);
        if (!buf || ms_sel_macro_get(name, buf, (size_t)len + 1) != len) {
            free(buf);
            return ms_cmd_error(interp, "atomselect macro: '%s' changed while reading it", name);
        }
        Tcl_SetObjResult(interp, Tcl_NewStringObj(buf, len));
        free(buf);
        return TCL_OK;
    }
    if (ms_sel_macro_define(name, Tcl_GetString(objv[3]), &err))
        return ms_cmd_error(interp, "atomselect macro: %s", err.msg);
    return TCL_OK;
}

static int delmacro_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_error err = {{0}};
    if (ms_sel_macro_delete(Tcl_GetString(objv[2]), &err))
        return ms_cmd_error(interp, "atomselect delmacro: %s", err.msg);
    return TCL_OK;
}

/* ---------------------------------------------------------------- $sel <method> ... */

static int atomsel_obj_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_atomsel *s = cd;
    atomsel_state *st = Tcl_GetAssocData(interp, "ms_atomsel", NULL);
    const size_t stride = sizeof *ms_atomsel_methods;
    const char *w = objc > 1 ? Tcl_GetString(objv[1]) : NULL;
    if (!w) return ms_args_unknown(interp, s->name, "method", NULL, ms_atomsel_methods, stride);
    int k = ms_args_find(ms_atomsel_methods, stride, w), typed = 0;
    /* write<type>: writepdb, writexyz ... (a prefix, the one word not matched whole) */
    if (k < 0 && !strncasecmp(w, "write", 5) && w[5]) {
        k = ms_args_find(ms_atomsel_methods, stride, "write<type>");
        typed = 1;
    }
    if (k < 0) return ms_args_unknown(interp, s->name, "method", w, ms_atomsel_methods, stride);
    const struct ms_atomsel_method *m = &ms_atomsel_methods[k];
    ms_args_frame call;
    if (ms_args_enter(&call, interp, s->name, typed ? w : m->name, m->usage, objc - 2, m->min,
                      m->max))
        return TCL_ERROR;
    if (m->changes) st->app->world.scene_version++;   /* atoms or bonds change, and the reps */
    int rc = m->fn(st->app, interp, s, objc, objv);
    ms_args_leave(&call);
    return rc;
}

/* ---------------------------------------------------------------- registration */

int ms_atomsel_resolve(ms_app *app, Tcl_Interp *interp, const char *name, const char *cmd,
                       int *molid, long *frame, uint32_t **atoms, size_t *natoms)
{
    ms_atomsel *s = ms_atomsel_lookup(app, interp, name, cmd);
    if (!s || !ms_atomsel_fresh(app, interp, s, cmd)) return TCL_ERROR;
    uint32_t *copy = ms_alloc_array(s->count, sizeof *copy);
    if (!copy) return ms_cmd_error(interp, "%s: out of memory", cmd);
    memcpy(copy, s->indices, s->count * sizeof *copy);
    *molid = s->molid;
    *frame = ms_atomsel_frame(app, s);
    *atoms = copy;
    *natoms = s->count;
    return TCL_OK;
}

static void state_free(ClientData cd, Tcl_Interp *interp) { free(cd); }

void ms_atomsel_register(ms_app *app)
{
    atomsel_state *st = calloc(1, sizeof *st);
    if (!st) return;
    st->app = app;
    static const ms_subcmd table[] = {
        {"list", list_selections, 0, 0, ""},
        {"keywords", list_keywords, 0, 0, ""},
        {"symboltable", list_keywords, 0, 0, ""},
        {"macro", macro_cmd, 0, 2, "?<name> ?<definition>??"},
        {"delmacro", delmacro_cmd, 1, 1, "<name>"},
        {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd create = {"<molid>", atomsel_create, 2, 4,
                                     "<molid> <selection text> ?frame <n|first|last|now>?"};
    static const ms_subcmd cmds[] = {
        {"upproc", cmd_upproc, 2, 2, "<level> <procname>"},
        {"::molscope::upproc_tie", cmd_tie, 1, 1, "<name>"}};
    Tcl_SetAssocData(app->interp, "ms_atomsel", state_free, st);
    ms_cmdset_create(app, "atomselect", table);
    ms_cmdset_fallback(app, "atomselect", &create);
    ms_cmdset_quiet(app, "atomselect");
    Tcl_Eval(app->interp, "namespace eval ::molscope {}");
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
