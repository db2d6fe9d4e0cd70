/* args.c: the argument layer of the Tcl commands (args.h): table dispatch with counts
 * checked once, keyword lookup with "must be" lists made from the tables, typed value
 * readers and the option-list parser, all with one error style. Knows Tcl and base.h only
 * (the molscope::parallel package links it too). */
#include "config.h"
#include "commands/args.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The innermost handler running (a stack through the C stack: a handler that evaluates a
 * script enters and leaves nested calls). */
static _Thread_local ms_args_frame *innermost;

int ms_cmd_error(Tcl_Interp *interp, const char *fmt, ...)
{
    char buf[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(buf, -1));
    return TCL_ERROR;
}

Tcl_Obj *ms_args_joined(int objc, Tcl_Obj *const objv[], int from)
{
    Tcl_Obj *s = Tcl_NewObj();
    for (int i = from; i < objc; i++) {
        if (i > from) Tcl_AppendToObj(s, " ", 1);
        Tcl_AppendObjToObj(s, objv[i]);
    }
    return s;
}

/* "<where>: " or "" */
static Tcl_Obj *prefixed(const char *where)
{
    return where && *where ? Tcl_ObjPrintf("%s: ", where) : Tcl_NewObj();
}

/* ---------------------------------------------------------------- calls */

const char *ms_args_where(void)
{
    ms_args_frame *c = innermost;
    if (!c) return "";
    if (!c->where[0])   /* made when first asked for: most calls never need it */
        snprintf(c->where, sizeof c->where, "%s%s%s", c->prefix, c->name && *c->prefix ? " " : "",
                 c->name ? c->name : "");
    return c->where;
}

int ms_args_usage(Tcl_Interp *interp)
{
    const ms_args_frame *c = innermost;
    if (!c) return ms_cmd_error(interp, "wrong # args");
    const char *where = ms_args_where();
    if (c->max == 0) return ms_cmd_error(interp, "%s: takes no arguments", where);
    return ms_cmd_error(interp, "%s: wrong # args: usage: %s%s%s", where, where,
                        *c->usage ? " " : "", c->usage);
}

int ms_args_enter(ms_args_frame *c, Tcl_Interp *interp, const char *prefix, const char *name,
                  const char *usage, int nargs, int min, int max)
{
    c->prefix = prefix;
    c->name = name;
    c->where[0] = '\0';
    c->usage = usage ? usage : "";
    c->max = max;
    c->outer = innermost;
    innermost = c;
    if (nargs >= min && (max < 0 || nargs <= max)) return TCL_OK;
    ms_args_usage(interp);
    ms_args_leave(c);
    return TCL_ERROR;
}

void ms_args_leave(ms_args_frame *c)
{
    innermost = c->outer;
}

int ms_args_call(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int first,
                 const ms_subcmd *e, const char *prefix, int fallback)
{
    ms_args_frame c;
    if (ms_args_enter(&c, interp, prefix, fallback ? NULL : e->name, e->usage, objc - first,
                      e->min, e->max) != TCL_OK)
        return TCL_ERROR;
    int rc = e->fn(app, interp, objc, objv);
    ms_args_leave(&c);
    return rc;
}

/* ---------------------------------------------------------------- keywords */

/* The name of entry i of a table of structs starting with their name. */
#define ENTRY(table, stride, i) \
    (*(const char *const *)((const char *)(table) + (size_t)(i) * (stride)))

int ms_args_find(const void *table, size_t stride, const char *word)
{
    for (int i = 0; ENTRY(table, stride, i); i++)
        if (ms_word_eq(word, ENTRY(table, stride, i))) return i;
    return -1;
}

/* "a", "a or b", "a, b, or c" (Tcl's form), leaving out entries skip says to. */
static void append_names(Tcl_Obj *msg, const void *table, size_t stride,
                         int (*skip)(const void *entry))
{
    int n = 0, total = 0;
    for (int i = 0; ENTRY(table, stride, i); i++)
        total += !(skip && skip((const char *)table + (size_t)i * stride));
    for (int i = 0; ENTRY(table, stride, i); i++) {
        if (skip && skip((const char *)table + (size_t)i * stride)) continue;
        if (n > 0) Tcl_AppendToObj(msg, n + 1 == total ? (total > 2 ? ", or " : " or ") : ", ", -1);
        Tcl_AppendToObj(msg, ENTRY(table, stride, i), -1);
        n++;
    }
}

/* "<where>: unknown <what> \"word\": must be ..." ("missing <what>" when word is NULL). */
static int unknown(Tcl_Interp *interp, const char *where, const char *what, const char *word,
                   const void *table, size_t stride, int (*skip)(const void *entry))
{
    Tcl_Obj *msg = prefixed(where);
    if (word) Tcl_AppendPrintfToObj(msg, "unknown %s \"%s\": must be ", what, word);
    else Tcl_AppendPrintfToObj(msg, "missing %s: must be ", what);
    append_names(msg, table, stride, skip);
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

int ms_args_unknown(Tcl_Interp *interp, const char *where, const char *what, const char *word,
                    const void *table, size_t stride)
{
    return unknown(interp, where, what, word, table, stride, NULL);
}

/* "<where>: bad value '<word>'[ for <what>]: must be " with the rest to append. */
static Tcl_Obj *bad_value_msg(Tcl_Obj *word, const char *what)
{
    Tcl_Obj *msg = prefixed(ms_args_where());
    Tcl_AppendPrintfToObj(msg, "bad value '%s'", Tcl_GetString(word));
    if (what) Tcl_AppendPrintfToObj(msg, " for %s", what);
    Tcl_AppendToObj(msg, ": must be ", -1);
    return msg;
}

static int bad_value(Tcl_Interp *interp, Tcl_Obj *word, const char *what, const char *expected)
{
    if (!interp) return TCL_ERROR;
    Tcl_Obj *msg = bad_value_msg(word, what);
    Tcl_AppendToObj(msg, expected, -1);
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

int ms_arg_choice(Tcl_Interp *interp, Tcl_Obj *word, const char *const *names, const char *what,
                  int *index)
{
    if ((*index = ms_args_find(names, sizeof *names, Tcl_GetString(word))) >= 0) return TCL_OK;
    if (!interp) return TCL_ERROR;
    Tcl_Obj *msg = bad_value_msg(word, what);
    append_names(msg, names, sizeof *names, NULL);
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

/* ---------------------------------------------------------------- values */

/* What a number within [lo, hi] is, in words ("a whole number from 0 to 30"). Bounds past
 * ±1e15 (and INT_MAX) are no bounds; above: lo itself is refused. */
static void number_text(char *buf, size_t n, int integer, double lo, double hi, int above)
{
    int has_lo = lo > -1e15 && !(integer && lo <= INT_MIN);
    int has_hi = hi < 1e15 && !(integer && hi >= INT_MAX);
    const char *noun = !integer ? "a number" : lo >= 0 ? "a whole number" : "an integer";
    if (above && has_hi) snprintf(buf, n, "%s above %.15g and at most %.15g", noun, lo, hi);
    else if (above) snprintf(buf, n, "%s above %.15g", noun, lo);
    else if (has_lo && has_hi) snprintf(buf, n, "%s from %.15g to %.15g", noun, lo, hi);
    else if (has_lo && !(integer && lo == 0)) snprintf(buf, n, "%s of at least %.15g", noun, lo);
    else if (has_hi) snprintf(buf, n, "%s of at most %.15g", noun, hi);
    else snprintf(buf, n, "%s", noun);
}

/* An integer; clamp: out of [lo, hi] is clamped instead of refused. */
static int read_long(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, long lo, long hi,
                     int clamp, long *out)
{
    Tcl_WideInt v;
    if (Tcl_GetWideIntFromObj(NULL, obj, &v) == TCL_OK && v >= LONG_MIN && v <= LONG_MAX &&
        (clamp || (v >= lo && v <= hi))) {
        *out = v < lo ? lo : v > hi ? hi : (long)v;
        return TCL_OK;
    }
    char text[96];
    number_text(text, sizeof text, 1, clamp ? -1e300 : (double)lo, clamp ? 1e300 : (double)hi, 0);
    return bad_value(interp, obj, what, text);
}

int ms_arg_long(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, long lo, long hi, long *out)
{
    return read_long(interp, obj, what, lo, hi, 0, out);
}

int ms_arg_int(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, long lo, long hi, int *out)
{
    long v;
    if (read_long(interp, obj, what, MS_MAX(lo, (long)INT_MIN), MS_MIN(hi, (long)INT_MAX), 0, &v))
        return TCL_ERROR;
    *out = (int)v;
    return TCL_OK;
}

int ms_arg_long_or(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, const char *const *words,
                   long lo, long hi, int *word, long *out)
{
    if ((*word = ms_args_find(words, sizeof *words, Tcl_GetString(obj))) >= 0) return TCL_OK;
    if (read_long(NULL, obj, what, lo, hi, 0, out) == TCL_OK) return TCL_OK;
    if (!interp) return TCL_ERROR;
    char text[96];
    int n = 0;
    while (words[n]) n++;
    number_text(text, sizeof text, 1, (double)lo, (double)hi, 0);
    Tcl_Obj *msg = bad_value_msg(obj, what);
    for (int i = 0; i < n; i++) Tcl_AppendPrintfToObj(msg, "%s%s", words[i], n > 1 ? ", " : " ");
    Tcl_AppendPrintfToObj(msg, "or %s", text);
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

/* A finite number within [lo, hi] (above: lo refused), or clamped to it. */
static int read_double(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, double lo, double hi,
                       int above, int clamp, double *out)
{
    double v;
    if (Tcl_GetDoubleFromObj(NULL, obj, &v) == TCL_OK && isfinite(v) &&
        (clamp || ((above ? v > lo : v >= lo) && v <= hi))) {
        *out = v < lo ? lo : v > hi ? hi : v;
        return TCL_OK;
    }
    char text[96];
    number_text(text, sizeof text, 0, clamp ? -HUGE_VAL : lo, clamp ? HUGE_VAL : hi,
                above && !clamp);
    return bad_value(interp, obj, what, text);
}

int ms_arg_double(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, double *out)
{
    return read_double(interp, obj, what, -HUGE_VAL, HUGE_VAL, 0, 0, out);
}

int ms_arg_double_range(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, double lo, double hi,
                        double *out)
{
    return read_double(interp, obj, what, lo, hi, 0, 0, out);
}

int ms_arg_float(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, float *out)
{
    double d;
    if (read_double(interp, obj, what, -FLT_MAX, FLT_MAX, 0, 0, &d)) return TCL_ERROR;
    *out = (float)d;
    return TCL_OK;
}

int ms_arg_bool(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, int *out)
{
    if (Tcl_GetBooleanFromObj(NULL, obj, out) == TCL_OK) return TCL_OK;
    return bad_value(interp, obj, what, "on, off, yes, no, true, false, 1, or 0");
}

int ms_arg_vec3(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, float v[3])
{
    Tcl_Obj **e;
    int n;
    double d[3];
    if (Tcl_ListObjGetElements(NULL, obj, &n, &e) != TCL_OK || n != 3) goto bad;
    for (int k = 0; k < 3; k++)
        if (Tcl_GetDoubleFromObj(NULL, e[k], &d[k]) != TCL_OK || !isfinite(d[k])) goto bad;
    for (int k = 0; k < 3; k++) v[k] = (float)d[k];
    return TCL_OK;
bad:
    return bad_value(interp, obj, what, "three numbers {x y z}");
}

/* ---------------------------------------------------------------- option lists */

static int is_alias(const void *entry)
{
    return (((const ms_opt *)entry)->flags & MS_OPT_ALIAS) != 0;
}

static int option_value(Tcl_Interp *interp, const ms_opt *o, Tcl_Obj *v, void *target)
{
    double lo = o->flags & (MS_OPT_MIN | MS_OPT_ABOVE) ? o->lo : -HUGE_VAL;
    double hi = o->flags & MS_OPT_MAX ? o->hi : HUGE_VAL;
    int above = (o->flags & MS_OPT_ABOVE) != 0, clamp = (o->flags & MS_OPT_CLAMP) != 0;
    long l;
    double d;
    switch (o->type) {
    case MS_OPT_BOOL:
        return ms_arg_bool(interp, v, o->name, target);
    case MS_OPT_INT:
    case MS_OPT_LONG: {
        long llo = o->type == MS_OPT_INT ? INT_MIN : LONG_MIN;
        long lhi = o->type == MS_OPT_INT ? INT_MAX : LONG_MAX;
        if (lo > -HUGE_VAL) llo = (long)lo + above;
        if (hi < HUGE_VAL) lhi = (long)hi;
        if (read_long(interp, v, o->name, llo, lhi, clamp, &l)) return TCL_ERROR;
        if (o->type == MS_OPT_INT) *(int *)target = (int)l;
        else *(long *)target = l;
        return TCL_OK;
    }
    case MS_OPT_DOUBLE:
    case MS_OPT_FLOAT:
        if (read_double(interp, v, o->name, lo, hi, above, clamp, &d)) return TCL_ERROR;
        if (o->type == MS_OPT_FLOAT) *(float *)target = (float)d;
        else *(double *)target = d;
        return TCL_OK;
    case MS_OPT_STRING:
        *(const char **)target = Tcl_GetString(v);
        return TCL_OK;
    case MS_OPT_OBJ:
        *(Tcl_Obj **)target = v;
        return TCL_OK;
    case MS_OPT_ENUM:
        return ms_arg_choice(interp, v, o->choices, o->name, target);
    case MS_OPT_FLAG:
    case MS_OPT_IGNORE:
        return TCL_OK;
    }
    return TCL_OK;
}

int ms_args_options(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int first,
                    const ms_opt *table, void *dst, Tcl_Obj **trailing)
{
    unsigned char seen[64] = {0};
    if (trailing) *trailing = NULL;
    for (int i = first; i < objc; i++) {
        const char *w = Tcl_GetString(objv[i]);
        int k = ms_args_find(table, sizeof *table, w);
        const ms_opt *o = k >= 0 ? &table[k] : NULL;
        if (!(o && o->type == MS_OPT_FLAG) && i + 1 >= objc && trailing) {
            *trailing = objv[i];
            return TCL_OK;
        }
        if (!o)
            return unknown(interp, ms_args_where(), "option", w, table, sizeof *table, is_alias);
        if (k < (int)sizeof seen) {
            if (seen[k] && (o->flags & MS_OPT_ONCE)) {
                Tcl_Obj *msg = prefixed(ms_args_where());
                Tcl_AppendPrintfToObj(msg, "option \"%s\" given twice", o->name);
                Tcl_SetObjResult(interp, msg);
                return TCL_ERROR;
            }
            seen[k] = 1;
        }
        char *target = (char *)dst + o->off;
        if (o->type == MS_OPT_FLAG) {
            *(int *)target = 1;
            continue;
        }
        if (i + 1 >= objc) {
            Tcl_Obj *msg = prefixed(ms_args_where());
            Tcl_AppendPrintfToObj(msg, "no value for option \"%s\"", w);
            Tcl_SetObjResult(interp, msg);
            return TCL_ERROR;
        }
        if (option_value(interp, o, objv[++i], target) != TCL_OK) return TCL_ERROR;
    }
    return TCL_OK;
}

/* ---------------------------------------------------------------- dispatch */

int ms_args_dispatch(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int at,
                     const ms_subcmd *table, const ms_subcmd *fallback, const char *where)
{
    if (!where) where = ms_args_where();
    if (at >= objc) return unknown(interp, where, "subcommand", NULL, table, sizeof *table, NULL);
    const char *w = Tcl_GetString(objv[at]);
    int k = ms_args_find(table, sizeof *table, w);
    if (k >= 0) return ms_args_call(app, interp, objc, objv, at + 1, &table[k], where, 0);
    if (fallback) return ms_args_call(app, interp, objc, objv, at, fallback, where, 1);
    return unknown(interp, where, "subcommand", w, table, sizeof *table, NULL);
}
