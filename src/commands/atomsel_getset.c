/* atomsel_getset.c: `$sel get {keywords}` and `$sel set {keywords} {values}`.
 *
 * get: one keyword gives a flat list, several give one list per atom; singlewords and macros
 * give 0/1. set: one value for every atom, one per atom, or (several keywords) one list per
 * atom. Every value is checked before anything changes. */
#include "config.h"
#include "commands/atomsel_int.h"
#include "commands/commands.h"

#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- get */

/* 0/1 per selected atom of a macro, evaluated as a selection on the same frame. */
static int macro_column(ms_atomsel *s, ms_molecule *m, const char *name, Tcl_Obj **col,
                        ms_error *err)
{
    ms_bitset bits;
    if (ms_sel_select(m, s->frame, name, &bits, err)) return -1;
    for (size_t q = 0; q < s->count; q++)
        col[q] = Tcl_NewIntObj(ms_bitset_get(&bits, s->indices[q]));
    ms_bitset_free(&bits);
    return 0;
}

static int number_column(const ms_selkw *k, ms_atomsel *s, ms_molecule *m, Tcl_Obj **col,
                         ms_error *err)
{
    double *v = ms_alloc_array(s->count, sizeof *v);
    if (!v) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    int rc = ms_sel_get_numbers(k, m, s->frame, s->indices, s->count, v, err);
    ms_selkw_type t = ms_sel_keyword_type(k);
    for (size_t q = 0; rc == 0 && q < s->count; q++)
        col[q] = t == MS_SELKW_FLOAT ? Tcl_NewDoubleObj(v[q])
                                     : Tcl_NewWideIntObj((Tcl_WideInt)v[q]);
    free(v);
    return rc;
}

static int string_column(const ms_selkw *k, ms_atomsel *s, ms_molecule *m, Tcl_Obj **col,
                         ms_error *err)
{
    const char **v = ms_alloc_array(s->count, sizeof *v);
    if (!v) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    int rc = ms_sel_get_strings(k, m, s->frame, s->indices, s->count, v, err);
    for (size_t q = 0; rc == 0 && q < s->count; q++) col[q] = Tcl_NewStringObj(v[q], -1);
    free(v);
    return rc;
}

static int column(ms_atomsel *s, ms_molecule *m, const char *name, Tcl_Obj **col,
                  ms_error *err)
{
    const ms_selkw *k = ms_sel_keyword(name);
    if (!k) {
        if (ms_sel_macro_get(name, NULL, 0) >= 0) return macro_column(s, m, name, col, err);
        ms_error_set(err, "unknown keyword '%s'", name);
        return -1;
    }
    switch (ms_sel_keyword_type(k)) {
    case MS_SELKW_STRING: return string_column(k, s, m, col, err);
    case MS_SELKW_INT: case MS_SELKW_FLOAT: case MS_SELKW_BOOL:
        return number_column(k, s, m, col, err);
    default:
        ms_error_set(err, "'%s' is not a keyword or singleword", name);
        return -1;
    }
}

int ms_atomsel_get(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                   Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, "get");
    if (!m) return TCL_ERROR;
    Tcl_Obj **keys;
    int nk;
    if (Tcl_ListObjGetElements(NULL, objv[2], &nk, &keys) != TCL_OK)
        return ms_atomsel_error(interp, s, "get", "bad keyword list '%.100s'",
                                Tcl_GetString(objv[2]));
    Tcl_Obj **cols = ms_calloc_array((size_t)nk * (s->count ? s->count : 1), sizeof *cols);
    Tcl_Obj **row = ms_alloc_array((size_t)nk + 1, sizeof *row);
    ms_error err = {{0}};
    int rc = cols && row ? TCL_OK : ms_atomsel_error(interp, s, "get", "out of memory");
    for (int k = 0; rc == TCL_OK && k < nk; k++)
        if (column(s, m, Tcl_GetString(keys[k]), cols + (size_t)k * s->count, &err))
            rc = ms_atomsel_error(interp, s, "get", "%s", err.msg);
    if (rc == TCL_OK && nk == 1) {
        Tcl_SetObjResult(interp, Tcl_NewListObj((int)s->count, cols));
    } else if (rc == TCL_OK) {
        Tcl_Obj *out = Tcl_NewListObj(0, NULL);
        for (size_t q = 0; q < s->count; q++) {
            for (int k = 0; k < nk; k++) row[k] = cols[(size_t)k * s->count + q];
            Tcl_ListObjAppendElement(NULL, out, Tcl_NewListObj(nk, row));
        }
        Tcl_SetObjResult(interp, out);
    }
    if (rc != TCL_OK && cols)   /* objects made before the failure were never used */
        for (size_t q = 0; q < (size_t)nk * s->count; q++)
            if (cols[q]) {
                Tcl_IncrRefCount(cols[q]);
                Tcl_DecrRefCount(cols[q]);
            }
    free(cols);
    free(row);
    return rc;
}

/* ---------------------------------------------------------------- set */

typedef struct setcol {
    const ms_selkw *kw;
    double *num;
    const char **str;
} setcol;

/* One value of keyword k from word o (ints: an integer, or a number truncated). */
static int parse_value(const ms_selkw *k, Tcl_Obj *o, setcol *c, size_t q)
{
    ms_selkw_type t = ms_sel_keyword_type(k);
    if (t == MS_SELKW_STRING) {
        c->str[q] = Tcl_GetString(o);
        return 0;
    }
    Tcl_WideInt w;
    if (t == MS_SELKW_INT && Tcl_GetWideIntFromObj(NULL, o, &w) == TCL_OK) {
        c->num[q] = (double)w;
        return 0;
    }
    return Tcl_GetDoubleFromObj(NULL, o, &c->num[q]) == TCL_OK ? 0 : -1;
}

/* The value of atom q for keyword column k: the one value, one per atom, or one list per
 * atom (several keywords). */
static Tcl_Obj *value_word(Tcl_Obj **vals, int nv, int nk, int k, size_t q)
{
    if (nk == 1) return vals[nv == 1 ? 0 : q];
    Tcl_Obj **items;
    int ni;
    if (Tcl_ListObjGetElements(NULL, vals[q], &ni, &items) != TCL_OK || ni != nk) return NULL;
    return items[k];
}

static int check_keys(Tcl_Interp *interp, ms_atomsel *s, Tcl_Obj **keys, int nk, setcol *cols)
{
    for (int k = 0; k < nk; k++) {
        const char *name = Tcl_GetString(keys[k]);
        const ms_selkw *kw = ms_sel_keyword(name);
        if (!kw) return ms_atomsel_error(interp, s, "set", "unknown keyword '%s'", name);
        ms_selkw_type t = ms_sel_keyword_type(kw);
        if (!ms_sel_keyword_settable(kw) || t > MS_SELKW_STRING)
            return ms_atomsel_error(interp, s, "set", "'%s' cannot be set", name);
        cols[k].kw = kw;
        cols[k].num = t == MS_SELKW_STRING ? NULL : ms_alloc_array(s->count, sizeof(double));
        cols[k].str = t == MS_SELKW_STRING ? ms_alloc_array(s->count, sizeof(char *)) : NULL;
        if (!cols[k].num && !cols[k].str)
            return ms_atomsel_error(interp, s, "set", "out of memory");
    }
    return TCL_OK;
}

static int parse_values(Tcl_Interp *interp, ms_atomsel *s, Tcl_Obj **vals, int nv, int nk,
                        setcol *cols)
{
    if (nk == 1 ? (nv != 1 && (size_t)nv != s->count) : (size_t)nv != s->count)
        return ms_atomsel_error(interp, s, "set", "%d values for %zu selected atoms", nv,
                                s->count);
    for (size_t q = 0; q < s->count; q++)
        for (int k = 0; k < nk; k++) {
            Tcl_Obj *w = value_word(vals, nv, nk, k, q);
            if (!w)
                return ms_atomsel_error(interp, s, "set", "value %zu '%.100s' should be a list "
                                        "of %d values", q, Tcl_GetString(vals[q]), nk);
            if (parse_value(cols[k].kw, w, &cols[k], q))
                return ms_atomsel_error(interp, s, "set", "bad value '%.100s' for %s",
                                        Tcl_GetString(w), ms_sel_keyword_name(cols[k].kw));
        }
    return TCL_OK;
}

int ms_atomsel_set(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                   Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, "set");
    if (!m) return TCL_ERROR;
    Tcl_Obj **keys, **vals;
    int nk, nv;
    if (Tcl_ListObjGetElements(NULL, objv[2], &nk, &keys) != TCL_OK || nk == 0)
        return ms_atomsel_error(interp, s, "set", "bad keyword list '%.100s'",
                                Tcl_GetString(objv[2]));
    if (Tcl_ListObjGetElements(NULL, objv[3], &nv, &vals) != TCL_OK)
        return ms_atomsel_error(interp, s, "set", "bad value list '%.100s'",
                                Tcl_GetString(objv[3]));
    setcol *cols = ms_calloc_array((size_t)nk, sizeof *cols);
    if (!cols) return ms_atomsel_error(interp, s, "set", "out of memory");
    int rc = check_keys(interp, s, keys, nk, cols);
    if (rc == TCL_OK) rc = parse_values(interp, s, vals, nv, nk, cols);
    int coords = 0, attrs = 0;
    ms_error err = {{0}};
    for (int k = 0; rc == TCL_OK && k < nk; k++) {
        const char *nm = ms_sel_keyword_name(cols[k].kw);
        int is_coord = strlen(nm) <= 2 && (nm[0] == 'x' || nm[0] == 'y' || nm[0] == 'z' ||
                                           nm[0] == 'v');
        if (is_coord && m->nframes == 0) continue;   /* VMD ignores it: nothing to set */
        coords |= is_coord;
        attrs |= !is_coord;
        int r = cols[k].str ? ms_sel_set_strings(cols[k].kw, m, s->frame, s->indices, s->count,
                                                 cols[k].str, &err)
                            : ms_sel_set_numbers(cols[k].kw, m, s->frame, s->indices, s->count,
                                                 cols[k].num, &err);
        if (r) rc = ms_atomsel_error(interp, s, "set", "%s", err.msg);
    }
    for (int k = 0; k < nk; k++) {
        free(cols[k].num);
        free((void *)cols[k].str);
    }
    free(cols);
    if (coords) ms_molset_emit(&app->mols, MS_EV_FRAME, m, NULL);
    if (attrs) ms_molset_emit(&app->mols, MS_EV_STRUCTURE, m, NULL);
    return rc;
}
