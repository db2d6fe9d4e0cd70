/* cmd_label.c: VMD's `label` command (assemble/labels.h holds the labels):
 *
 *   label add Atoms|Bonds|Angles|Dihedrals <molid>/<atom> ...   (1 to 4 atoms: the index)
 *   label list ?<category>?          (no category: the category names)
 *   label show|hide|delete <category> ?<n>|all?
 *   label textsize ?<size>?          label textthickness ?<thickness>?
 *   label textoffset <category> <n> ?{x y}?
 *   label textformat <category> <n> ?<format>?
 *   label graph <category> <n>       (the value at every frame, as a list)
 *
 * `label list` answers one element per label: the atoms as {molid index} pairs, the value and
 * show or hide, as VMD does. */
#include "config.h"
#include "commands/scenecmds.h"

#include <stdlib.h>
#include <string.h>

static ms_labels *labels(ms_app *app)
{
    return &app->world.labels;
}

static int category(Tcl_Interp *interp, Tcl_Obj *word, int *cat)
{
    static const char *const names[] = {"Atoms", "Bonds", "Angles", "Dihedrals", NULL};
    return ms_arg_choice(interp, word, names, "category", cat);
}

/* Label n of the category at objv[2], n at objv[3]. */
static ms_label *one_label(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[], int *catp)
{
    int cat, n;
    ms_labels *L = labels(app);
    if (category(interp, objv[2], &cat)) return NULL;
    if (Tcl_GetIntFromObj(NULL, objv[3], &n) != TCL_OK || n < 0 || (size_t)n >= L->n[cat]) {
        ms_cmd_error(interp, "%s: no label %s in %s (there are %zu)", ms_args_where(),
                     Tcl_GetString(objv[3]), ms_label_cat_name(cat), L->n[cat]);
        return NULL;
    }
    if (catp) *catp = cat;
    return &L->v[cat][n];
}

/* "<molid>/<atom>" */
static int atom_spec(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, int *mol, uint32_t *atom)
{
    const char *s = Tcl_GetString(word), *slash = strchr(s, '/');
    if (!slash)
        return ms_cmd_error(interp, "%s: bad atom '%s': must be <molid>/<atom index>", ms_args_where(), s);
    Tcl_Obj *m = Tcl_NewStringObj(s, (int)(slash - s));
    Tcl_IncrRefCount(m);
    ms_molecule *mp = ms_cmd_mol(app, interp, m, ms_args_where());
    Tcl_DecrRefCount(m);
    long a;
    if (!mp) return TCL_ERROR;
    Tcl_Obj *idx = Tcl_NewStringObj(slash + 1, -1);
    Tcl_IncrRefCount(idx);
    int rc = ms_arg_long(interp, idx, "atom index", 0, 0xfffffffeL, &a);
    Tcl_DecrRefCount(idx);
    if (rc) return TCL_ERROR;
    *mol = mp->id;
    *atom = (uint32_t)a;
    return TCL_OK;
}

static int l_add(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int cat, mol[4];
    uint32_t atom[4];
    if (category(interp, objv[2], &cat)) return TCL_ERROR;
    if (objc - 3 != cat + 1)
        return ms_cmd_error(interp, "%s: %s takes %d atoms, got %d", ms_args_where(),
                            ms_label_cat_name(cat), cat + 1, objc - 3);
    for (int i = 0; i <= cat; i++)
        if (atom_spec(app, interp, objv[3 + i], &mol[i], &atom[i])) return TCL_ERROR;
    ms_error err = {{0}};
    long k = ms_labels_add(labels(app), app->world.mols, cat, mol, atom, &err);
    if (k < 0) return ms_cmd_error(interp, "%s: %s", ms_args_where(), err.msg);
    Tcl_SetObjResult(interp, Tcl_NewLongObj(k));
    return TCL_OK;
}

static Tcl_Obj *label_obj(ms_app *app, const ms_label *l)
{
    Tcl_Obj *e = Tcl_NewListObj(0, NULL);
    double v = 0.0;
    for (int k = 0; k < l->n; k++) {
        Tcl_Obj *pair[2] = {Tcl_NewIntObj(l->mol[k]), Tcl_NewLongObj((long)l->atom[k])};
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewListObj(2, pair));
    }
    ms_label_value(app->world.mols, l, -1, &v);
    Tcl_ListObjAppendElement(NULL, e, Tcl_NewDoubleObj(v));
    Tcl_ListObjAppendElement(NULL, e, Tcl_NewStringObj(l->shown ? "show" : "hide", -1));
    return e;
}

static int l_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    int cat;
    if (objc == 2) {
        for (int c = 0; c < MS_LABEL_NCATS; c++)
            Tcl_ListObjAppendElement(NULL, out, Tcl_NewStringObj(ms_label_cat_name(c), -1));
    } else {
        if (category(interp, objv[2], &cat)) return TCL_ERROR;
        for (size_t i = 0; i < labels(app)->n[cat]; i++)
            Tcl_ListObjAppendElement(NULL, out, label_obj(app, &labels(app)->v[cat][i]));
    }
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

/* label show|hide|delete <category> ?<n>|all? */
static int l_state(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_labels *L = labels(app);
    const char *what = Tcl_GetString(objv[1]);
    int cat;
    long first = 0, last;
    if (category(interp, objv[2], &cat)) return TCL_ERROR;
    last = (long)L->n[cat] - 1;
    if (objc == 4 && !ms_word_eq(Tcl_GetString(objv[3]), "all")) {
        if (!one_label(app, interp, objv, NULL)) return TCL_ERROR;
        Tcl_GetLongFromObj(NULL, objv[3], &first);
        last = first;
    }
    if (ms_word_eq(what, "delete")) {
        for (long i = last; i >= first; i--) ms_labels_delete(L, cat, i);
        return TCL_OK;
    }
    for (long i = first; i <= last; i++) L->v[cat][i].shown = ms_word_eq(what, "show");
    return TCL_OK;
}

/* label textsize|textthickness ?<value>? */
static int l_text(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_labels *L = labels(app);
    float *v = ms_word_eq(Tcl_GetString(objv[1]), "textsize") ? &L->size : &L->thickness;
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewDoubleObj(*v));
        return TCL_OK;
    }
    double x;
    if (ms_arg_double_range(interp, objv[2], NULL, 0.0, 1000.0, &x)) return TCL_ERROR;
    *v = (float)x;
    return TCL_OK;
}

static int l_textoffset(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_label *l = one_label(app, interp, objv, NULL);
    if (!l) return TCL_ERROR;
    if (objc == 4) {
        Tcl_Obj *xy[2] = {Tcl_NewDoubleObj(l->offset[0]), Tcl_NewDoubleObj(l->offset[1])};
        Tcl_SetObjResult(interp, Tcl_NewListObj(2, xy));
        return TCL_OK;
    }
    Tcl_Obj **w;
    int n;
    double x, y;
    if (Tcl_ListObjGetElements(NULL, objv[4], &n, &w) != TCL_OK || n != 2)
        return ms_cmd_error(interp, "%s: bad offset '%s': must be {x y}", ms_args_where(),
                            Tcl_GetString(objv[4]));
    if (ms_arg_double(interp, w[0], "x", &x) || ms_arg_double(interp, w[1], "y", &y))
        return TCL_ERROR;
    l->offset[0] = (float)x;
    l->offset[1] = (float)y;
    return TCL_OK;
}

static int l_textformat(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_label *l = one_label(app, interp, objv, NULL);
    if (!l) return TCL_ERROR;
    if (objc == 4) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(l->format, -1));
        return TCL_OK;
    }
    int len;
    const char *f = Tcl_GetStringFromObj(objv[4], &len);
    if (len >= MS_LABEL_FORMAT_MAX)
        return ms_cmd_error(interp, "%s: format longer than %d characters", ms_args_where(),
                            MS_LABEL_FORMAT_MAX - 1);
    memcpy(l->format, f, (size_t)len + 1);
    return TCL_OK;
}

static int l_graph(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_label *l = one_label(app, interp, objv, NULL);
    if (!l) return TCL_ERROR;
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    long n = ms_label_frames(app->world.mols, l);
    for (long f = 0; f < n; f++) {
        double v = 0.0;
        ms_label_value(app->world.mols, l, f, &v);
        Tcl_ListObjAppendElement(NULL, out, Tcl_NewDoubleObj(v));
    }
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

void ms_cmd_label_register(ms_app *app)
{
    static const ms_subcmd table[] = {
        {"add", l_add, 2, 5, "Atoms|Bonds|Angles|Dihedrals <molid>/<atom> ?<molid>/<atom> ...?"},
        {"list", l_list, 0, 1, "?<category>?"},
        {"show", l_state, 1, 2, "<category> ?<n>|all?"},
        {"hide", l_state, 1, 2, "<category> ?<n>|all?"},
        {"delete", l_state, 1, 2, "<category> ?<n>|all?"},
        {"textsize", l_text, 0, 1, "?<size>?"},
        {"textthickness", l_text, 0, 1, "?<thickness>?"},
        {"textoffset", l_textoffset, 2, 3, "<category> <n> ?{x y}?"},
        {"textformat", l_textformat, 2, 3, "<category> <n> ?<format>?"},
        {"graph", l_graph, 2, 2, "<category> <n>"},
        {NULL, NULL, 0, 0, NULL}};
    ms_cmdset_create(app, "label", table);
}
