/* cmd_pbc.c: the `pbc` command of VMD's pbctools (doc/pbctools.md). The per-frame work is
 * C: the subcommands here parse VMD's options and call src/pbc:
 *
 *   pbc set cell ?-molid m? ?-first f? ?-last l? ?-all|-allframes? ?-now? ?-namd|-vmd?
 *   pbc get ?-molid m? ?-first f? ?-last l? ?-all? ?-now? ?-namd|-vmd?
 *   pbc wrap ?-sel s? ?-compound res|residue|seg|segid|chain|fragment|connected? ?-nocompound?
 *            ?-center origin|unitcell|com|centerofmass|bb|boundingbox? ?-centersel s?
 *            ?-shiftcenter v? ?-shiftcenterrel v? ?-orthorhombic|-parallelepiped? (+ frames)
 *   pbc unwrap ?-sel s? (+ frames)
 *   pbc join compound ?-sel s? ?-ref s? ?-bondlist? ?-border d? (+ frames)
 *
 * Frames: -first and -last take a frame number or first, last, now; -all is every frame,
 * -now the current one. readxst, box and box_draw are Tcl (tcl/pbctools/pbctools.tcl):
 * their entries here load the package and call it, so `pbc` needs no package require. */
#include "config.h"
#include "app/app.h"
#include "commands/commands.h"
#include "pbc/pbc.h"
#include "select/select.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct pbc_args {
    Tcl_Obj *molid, *first, *last;
    int all, now, namd, vmd, nocompound, compound, center, ortho, para, bondlist, ignored;
    const char *sel, *centersel, *ref;
    Tcl_Obj *shiftcenter, *shiftcenterrel;
} pbc_args;

static const char *const compound_names[] = {"res", "residue", "seg", "segid", "chain",
                                             "fragment", "connected", "bonded", NULL};
static const int compound_kind[] = {MS_PBC_RESIDUE, MS_PBC_RESIDUE, MS_PBC_SEGMENT,
                                    MS_PBC_SEGMENT, MS_PBC_CHAIN, MS_PBC_FRAGMENT,
                                    MS_PBC_CONNECTED, MS_PBC_CONNECTED};
static const char *const center_names[] = {"unitcell", "origin", "com", "centerofmass", "bb",
                                           "boundingbox", NULL};
static const int center_kind[] = {MS_PBC_CENTER_UNITCELL, MS_PBC_CENTER_ORIGIN,
                                  MS_PBC_CENTER_COM, MS_PBC_CENTER_COM, MS_PBC_CENTER_BB,
                                  MS_PBC_CENTER_BB};

#define A(f) offsetof(pbc_args, f)
#define FRAME_OPTIONS                                                   \
    {"-molid", MS_OPT_OBJ, A(molid), 0, 0, 0, NULL},                    \
    {"-first", MS_OPT_OBJ, A(first), 0, 0, 0, NULL},                    \
    {"-last", MS_OPT_OBJ, A(last), 0, 0, 0, NULL},                      \
    {"-all", MS_OPT_FLAG, A(all), 0, 0, 0, NULL},                       \
    {"-allframes", MS_OPT_FLAG, A(all), 0, 0, MS_OPT_ALIAS, NULL},      \
    {"-now", MS_OPT_FLAG, A(now), 0, 0, 0, NULL},                       \
    {"-verbose", MS_OPT_FLAG, A(ignored), 0, 0, 0, NULL}
#define END_OPTIONS {NULL, 0, 0, 0, 0, 0, NULL}
#define CELL_OPTIONS                                                    \
    {"-namd", MS_OPT_FLAG, A(namd), 0, 0, 0, NULL},                     \
    {"-vmd", MS_OPT_FLAG, A(vmd), 0, 0, 0, NULL}

static const ms_opt cell_options[] = {FRAME_OPTIONS, CELL_OPTIONS, END_OPTIONS};
static const ms_opt wrap_options[] = {
    FRAME_OPTIONS,
    {"-sel", MS_OPT_STRING, A(sel), 0, 0, 0, NULL},
    {"-compound", MS_OPT_ENUM, A(compound), 0, 0, 0, compound_names},
    {"-nocompound", MS_OPT_FLAG, A(nocompound), 0, 0, 0, NULL},
    {"-center", MS_OPT_ENUM, A(center), 0, 0, 0, center_names},
    {"-centersel", MS_OPT_STRING, A(centersel), 0, 0, 0, NULL},
    {"-shiftcenter", MS_OPT_OBJ, A(shiftcenter), 0, 0, 0, NULL},
    {"-shiftcenterrel", MS_OPT_OBJ, A(shiftcenterrel), 0, 0, 0, NULL},
    {"-orthorhombic", MS_OPT_FLAG, A(ortho), 0, 0, 0, NULL},
    {"-rectangular", MS_OPT_FLAG, A(ortho), 0, 0, MS_OPT_ALIAS, NULL},
    {"-parallelepiped", MS_OPT_FLAG, A(para), 0, 0, 0, NULL},
    END_OPTIONS};
static const ms_opt unwrap_options[] = {
    FRAME_OPTIONS, {"-sel", MS_OPT_STRING, A(sel), 0, 0, 0, NULL}, END_OPTIONS};
static const ms_opt join_options[] = {
    FRAME_OPTIONS,
    {"-sel", MS_OPT_STRING, A(sel), 0, 0, 0, NULL},
    {"-ref", MS_OPT_STRING, A(ref), 0, 0, 0, NULL},
    {"-bondlist", MS_OPT_FLAG, A(bondlist), 0, 0, 0, NULL},
    {"-border", MS_OPT_IGNORE, 0, 0, 0, 0, NULL},
    {"-noborder", MS_OPT_FLAG, A(ignored), 0, 0, 0, NULL},
    END_OPTIONS};

/* ---------------------------------------------------------------- options and frames */

/* Parse the options after objv[start]; the molecule (-molid, top by default) in *m. */
static int pbc_parse(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int start,
                     const ms_opt *table, pbc_args *a, ms_molecule **m)
{
    memset(a, 0, sizeof *a);
    a->compound = -1;
    if (ms_args_options(interp, objc, objv, start, table, a, NULL)) return TCL_ERROR;
    if (a->all && a->now)
        return ms_cmd_error(interp, "%s: -all and -now cannot be given together", ms_args_where());
    Tcl_Obj *top = Tcl_NewStringObj("top", -1);
    Tcl_IncrRefCount(top);
    *m = ms_cmd_mol(app, interp, a->molid ? a->molid : top, ms_args_where());
    Tcl_DecrRefCount(top);
    if (!*m) return TCL_ERROR;
    ms_app_finish_loading(app);
    if ((*m)->nframes == 0)
        return ms_cmd_error(interp, "%s: molecule %d has no frames", ms_args_where(), (*m)->id);
    return TCL_OK;
}

/* A frame word: a number, first, last or now. */
static int frame_word(Tcl_Interp *interp, Tcl_Obj *w, const ms_molecule *m, const char *what,
                      long *out)
{
    static const char *const words[] = {"first", "last", "now", NULL};
    int k;
    long v;
    if (ms_arg_long_or(interp, w, what, words, 0, INT_MAX, &k, &v)) return TCL_ERROR;
    long n = (long)m->nframes;
    *out = k == 0 ? 0 : k == 1 ? n - 1 : k == 2 ? (m->frame < 0 ? 0 : m->frame) : v;
    if (*out >= n)
        return ms_cmd_error(interp, "%s: molecule %d has no frame %ld (frames 0 to %ld)",
                            ms_args_where(), m->id, *out, n - 1);
    return TCL_OK;
}

/* The frame range: the defaults all_default (every frame) or the current frame, then
 * -all/-now, then -first/-last. */
static int frame_range(Tcl_Interp *interp, const pbc_args *a, const ms_molecule *m,
                       int all_default, size_t *first, size_t *last)
{
    long cur = m->frame < 0 ? 0 : m->frame, f, l;
    int all = a->all || (all_default && !a->now);
    f = all ? 0 : cur;
    l = all ? (long)m->nframes - 1 : cur;
    if (a->first && frame_word(interp, a->first, m, "-first", &f)) return TCL_ERROR;
    if (a->last && frame_word(interp, a->last, m, "-last", &l)) return TCL_ERROR;
    if (f > l)
        return ms_cmd_error(interp, "%s: first frame %ld is after last frame %ld", ms_args_where(),
                            f, l);
    *first = (size_t)f;
    *last = (size_t)l;
    return TCL_OK;
}

/* The options, the molecule and the frame range of a subcommand, in one call. */
static int pbc_begin(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int start,
                     const ms_opt *table, int all_default, pbc_args *a, ms_molecule **m,
                     size_t *first, size_t *last)
{
    if (pbc_parse(app, interp, objc, objv, start, table, a, m)) return TCL_ERROR;
    return frame_range(interp, a, *m, all_default, first, last);
}

/* The atoms of a selection text (evaluated on frame f), malloc'd, ascending. */
static int select_atoms(Tcl_Interp *interp, ms_molecule *m, size_t f, const char *text,
                        const char *what, uint32_t **atoms, size_t *n)
{
    ms_bitset bits;
    ms_error err = {{0}};
    if (ms_sel_select(m, (long)f, text ? text : "all", &bits, &err))
        return ms_cmd_error(interp, "%s: %s \"%s\": %s", ms_args_where(), what, text, err.msg);
    *n = 0;
    *atoms = ms_alloc_array(m->atoms.n ? m->atoms.n : 1, sizeof **atoms);
    for (size_t i = 0; *atoms && i < m->atoms.n; i++)
        if (ms_bitset_get(&bits, i)) (*atoms)[(*n)++] = (uint32_t)i;
    ms_bitset_free(&bits);
    if (!*atoms) return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    return TCL_OK;
}

static int core_error(Tcl_Interp *interp, const ms_error *err)
{
    return ms_cmd_error(interp, "%s: %s", ms_args_where(), err->msg);
}

/* Coordinates changed: reps and traces follow. */
static void coords_changed(ms_app *app, ms_molecule *m)
{
    ms_molset_emit(&app->mols, MS_EV_FRAME, m, NULL);
}

/* ---------------------------------------------------------------- set and get */

/* One cell: {a b c ?alpha beta gamma?}, or with namd {A B C} (three vectors). */
static int parse_cell(Tcl_Interp *interp, Tcl_Obj *obj, int namd, float cell[6])
{
    Tcl_Obj **w;
    int n;
    double v[3][3], d[6] = {0, 0, 0, 90, 90, 90};
    if (Tcl_ListObjGetElements(interp, obj, &n, &w) != TCL_OK) return TCL_ERROR;
    if (namd) {
        if (n != 3) goto bad;
        for (int i = 0; i < 3; i++) {
            float f[3];
            if (ms_arg_vec3(interp, w[i], "cell vector", f)) return TCL_ERROR;
            for (int k = 0; k < 3; k++) v[i][k] = f[k];
        }
        if (!ms_pbc_cell_params(v, cell)) goto bad;
        return TCL_OK;
    }
    if (n != 3 && n != 6) goto bad;
    for (int i = 0; i < n; i++)
        if (ms_arg_double(interp, w[i], "cell parameter", &d[i])) return TCL_ERROR;
    for (int i = 0; i < 6; i++) cell[i] = (float)d[i];
    ms_pbc_cell c;
    if (ms_pbc_cell_make(cell, &c)) return TCL_OK;
bad:
    return ms_cmd_error(interp, "%s: bad cell \"%s\": must be {a b c ?alpha beta gamma?} (or "
                        "{A B C} vectors with -namd) with lengths above 0 and angles that make "
                        "a cell", ms_args_where(), Tcl_GetString(obj));
}

/* Is obj a list of cells rather than one cell? */
static int is_cell_list(Tcl_Obj *obj, int namd)
{
    Tcl_Obj *e = obj;
    int n;
    for (int depth = 0; depth <= namd; depth++) {
        if (Tcl_ListObjIndex(NULL, e, 0, &e) != TCL_OK || !e) return 0;
        if (Tcl_ListObjLength(NULL, e, &n) != TCL_OK || n < 2) return 0;
    }
    return 1;
}

static int pbc_set(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    pbc_args a;
    ms_molecule *m;
    size_t first, last;
    if (pbc_begin(app, interp, objc, objv, 3, cell_options, 1, &a, &m, &first, &last))
        return TCL_ERROR;
    size_t nf = last - first + 1;
    int list = is_cell_list(objv[2], a.namd), n = 1;
    Tcl_Obj **cells = (Tcl_Obj **)&objv[2];
    if (list && Tcl_ListObjGetElements(interp, objv[2], &n, &cells) != TCL_OK) return TCL_ERROR;
    if (list && (size_t)n != nf)
        return ms_cmd_error(interp, "pbc set: %d cells given for %zu frames (%zu to %zu)", n, nf,
                            first, last);
    float *values = ms_alloc_array((size_t)n, 6 * sizeof *values);
    if (!values) return ms_cmd_error(interp, "pbc set: out of memory");
    for (int i = 0; i < n; i++)
        if (parse_cell(interp, cells[i], a.namd, values + 6 * i)) {
            free(values);
            return TCL_ERROR;
        }
    for (size_t f = first; f <= last; f++)
        memcpy(m->frames[f].cell, values + 6 * (list ? f - first : 0), 6 * sizeof *values);
    free(values);
    coords_changed(app, m);
    return TCL_OK;
}

static Tcl_Obj *cell_obj(const float cell[6], int namd)
{
    Tcl_Obj *o = Tcl_NewListObj(0, NULL);
    ms_pbc_cell c;
    if (!namd) {
        for (int i = 0; i < 6; i++) Tcl_ListObjAppendElement(NULL, o, Tcl_NewDoubleObj(cell[i]));
        return o;
    }
    if (!ms_pbc_cell_make(cell, &c)) memset(&c, 0, sizeof c);
    for (int i = 0; i < 3; i++) {
        Tcl_Obj *v = Tcl_NewListObj(0, NULL);
        for (int k = 0; k < 3; k++) Tcl_ListObjAppendElement(NULL, v, Tcl_NewDoubleObj(c.v[i][k]));
        Tcl_ListObjAppendElement(NULL, o, v);
    }
    return o;
}

static int pbc_get(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    pbc_args a;
    ms_molecule *m;
    size_t first, last;
    if (pbc_begin(app, interp, objc, objv, 2, cell_options, 0, &a, &m, &first, &last))
        return TCL_ERROR;
    Tcl_Obj *r = Tcl_NewListObj(0, NULL);
    for (size_t f = first; f <= last; f++)
        Tcl_ListObjAppendElement(NULL, r, cell_obj(m->frames[f].cell, a.namd));
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

/* ---------------------------------------------------------------- wrap, unwrap, join */

static int shift_option(Tcl_Interp *interp, Tcl_Obj *w, const char *what, double out[3])
{
    float v[3] = {0, 0, 0};
    if (w && ms_arg_vec3(interp, w, what, v)) return TCL_ERROR;
    for (int k = 0; k < 3; k++) out[k] = v[k];
    return TCL_OK;
}

typedef struct wrap_run {
    uint32_t *atoms, *center;
    size_t n, ncenter;
    ms_pbc_groups groups;
} wrap_run;

static int wrap_prepare(Tcl_Interp *interp, ms_molecule *m, size_t first, const pbc_args *a,
                        ms_pbc_wrap_opts *o, wrap_run *w)
{
    memset(o, 0, sizeof *o);
    o->center = center_kind[a->center];
    o->orthorhombic = a->ortho;
    if (shift_option(interp, a->shiftcenter, "-shiftcenter", o->shiftcenter) ||
        shift_option(interp, a->shiftcenterrel, "-shiftcenterrel", o->shiftcenterrel) ||
        select_atoms(interp, m, first, a->sel, "-sel", &w->atoms, &w->n) ||
        select_atoms(interp, m, first, a->centersel, "-centersel", &w->center, &w->ncenter))
        return TCL_ERROR;
    o->centersel = w->center;
    o->ncentersel = w->ncenter;
    ms_error err = {{0}};
    int kind = a->nocompound || a->compound < 0 ? -1 : compound_kind[a->compound];
    if (ms_pbc_groups_make(m, kind, w->atoms, w->n, &w->groups, &err)) return core_error(interp, &err);
    o->groups = &w->groups;
    return TCL_OK;
}

static int pbc_wrap(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    pbc_args a;
    ms_molecule *m;
    size_t first, last;
    if (pbc_begin(app, interp, objc, objv, 2, wrap_options, 0, &a, &m, &first, &last))
        return TCL_ERROR;
    if (a.ortho && a.para)
        return ms_cmd_error(interp, "pbc wrap: -orthorhombic and -parallelepiped cannot be "
                            "given together");
    ms_pbc_wrap_opts o;
    wrap_run w = {0};
    int rc = wrap_prepare(interp, m, first, &a, &o, &w);
    ms_error err = {{0}};
    if (rc == TCL_OK && ms_pbc_wrap(m, first, last, &o, &err)) rc = core_error(interp, &err);
    free(w.atoms);
    free(w.center);
    ms_pbc_groups_free(&w.groups);
    if (rc == TCL_OK) coords_changed(app, m);
    return rc;
}

static int pbc_unwrap(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    pbc_args a;
    ms_molecule *m;
    size_t first, last, n;
    uint32_t *atoms;
    if (pbc_begin(app, interp, objc, objv, 2, unwrap_options, 1, &a, &m, &first, &last) ||
        select_atoms(interp, m, first, a.sel, "-sel", &atoms, &n))
        return TCL_ERROR;
    ms_error err = {{0}};
    int rc = ms_pbc_unwrap(m, first, last, atoms, n, &err) ? core_error(interp, &err) : TCL_OK;
    free(atoms);
    if (rc == TCL_OK) coords_changed(app, m);
    return rc;
}

/* -ref as a molecule-sized array of bytes (NULL when not given). */
static int ref_flags(Tcl_Interp *interp, ms_molecule *m, size_t f, const char *ref, uint8_t **out)
{
    uint32_t *atoms;
    size_t n;
    *out = NULL;
    if (!ref) return TCL_OK;
    if (select_atoms(interp, m, f, ref, "-ref", &atoms, &n)) return TCL_ERROR;
    *out = calloc(m->atoms.n ? m->atoms.n : 1, 1);
    for (size_t i = 0; *out && i < n; i++) (*out)[atoms[i]] = 1;
    free(atoms);
    return *out ? TCL_OK : ms_cmd_error(interp, "pbc join: out of memory");
}

static int pbc_join(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    pbc_args a;
    ms_molecule *m;
    size_t first, last, n;
    int kind;
    uint32_t *atoms = NULL;
    uint8_t *ref = NULL;
    if (ms_arg_choice(interp, objv[2], compound_names, "compound", &kind) ||
        pbc_begin(app, interp, objc, objv, 3, join_options, 0, &a, &m, &first, &last) ||
        ref_flags(interp, m, first, a.ref, &ref) ||
        select_atoms(interp, m, first, a.sel, "-sel", &atoms, &n)) {
        free(ref);
        return TCL_ERROR;
    }
    ms_pbc_groups g;
    ms_error err = {{0}};
    int rc = TCL_OK;
    if (ms_pbc_groups_make(m, compound_kind[kind], atoms, n, &g, &err) ||
        ms_pbc_join(m, first, last, &g, ref, a.bondlist, &err))
        rc = core_error(interp, &err);
    ms_pbc_groups_free(&g);
    free(atoms);
    free(ref);
    if (rc == TCL_OK) coords_changed(app, m);
    return rc;
}

/* ---------------------------------------------------------------- the Tcl part */

/* readxst, box, box_draw: ::PBCTools::<name> of the pbctools package, loaded on first use. */
static int pbc_tcl(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app;
    if (!Tcl_PkgRequire(interp, "pbctools", NULL, 0)) return TCL_ERROR;
    Tcl_Obj *cmd = Tcl_ObjPrintf("::PBCTools::pbc%s", Tcl_GetString(objv[1]));
    Tcl_Obj **words = ms_alloc_array((size_t)objc, sizeof *words);
    if (!words) return ms_cmd_error(interp, "pbc: out of memory");
    words[0] = cmd;
    for (int i = 2; i < objc; i++) words[i - 1] = objv[i];
    Tcl_IncrRefCount(cmd);
    int rc = Tcl_EvalObjv(interp, objc - 1, words, TCL_EVAL_GLOBAL);
    Tcl_DecrRefCount(cmd);
    free(words);
    return rc;
}

static const ms_subcmd pbc_table[] = {
    {"set", pbc_set, 1, MS_ARGS_ANY, "cell ?options?"},
    {"get", pbc_get, 0, MS_ARGS_ANY, "?options?"},
    {"wrap", pbc_wrap, 0, MS_ARGS_ANY, "?options?"},
    {"unwrap", pbc_unwrap, 0, MS_ARGS_ANY, "?options?"},
    {"join", pbc_join, 1, MS_ARGS_ANY, "compound ?options?"},
    {"readxst", pbc_tcl, 1, MS_ARGS_ANY, "xstfile ?options?"},
    {"box", pbc_tcl, 0, MS_ARGS_ANY, "?options?"},
    {"box_draw", pbc_tcl, 0, MS_ARGS_ANY, "?options?"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_pbc_register(ms_app *app)
{
    ms_cmdset_create(app, "pbc", pbc_table);
}
