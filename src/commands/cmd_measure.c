/* cmd_measure.c: the `measure` command, VMD's forms over atom selections:
 *
 *   measure center sel ?weight w?                 -> {x y z}
 *   measure sumweights sel weight w               -> the sum of the weights
 *   measure minmax sel ?-withradii?               -> {{xmin ymin zmin} {xmax ymax zmax}}
 *   measure rgyr sel ?weight w?                   -> radius of gyration
 *   measure rmsd sel1 sel2 ?weight w?             -> RMSD without fitting
 *   measure fit sel1 sel2 ?weight w? ?order idx?  -> 4x4 matrix moving sel1 onto sel2
 *   measure inertia sel ?-moments? ?-eigenvals?   -> {com {a1 a2 a3}} ?tensor? ?moments?
 *   measure avpos|rmsf sel ?first f? ?last l? ?step s?
 *   measure contacts cutoff sel1 ?sel2?           -> {{indices of sel1} {indices of sel2}}
 *   measure hbonds cutoff angle sel1 ?sel2?       -> {{donors} {acceptors} {hydrogens}}
 *   measure sasa srad sel ?-points var? ?-restrict sel? ?-samples n?   -> area
 *   measure gofr|rdf sel1 sel2 ?delta d? ?rmax r? ?usepbc b? ?selupdate b? ?first f?
 *           ?last l? ?step s?                      -> {r g(r) integral histogram {frames}}
 *
 * A weight is `none`, a floating-point atom keyword (mass, charge, beta, occupancy,
 * radius, user...) or a list of numbers, one per selected atom or one per atom of the
 * molecule; weights of two-selection commands come from the first. Selections are resolved
 * through ms_atomsel_resolve; nothing here changes a molecule (gofr with selupdate moves
 * the selections through the frames and puts them back). The numbers come from
 * src/measure. */
#include "config.h"
#include "commands/atomsel.h"
#include "commands/commands.h"
#include "commands/tclvec.h"
#include "measure/measure.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define SUBCMD(name) static int name(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])

/* ---------------------------------------------------------------- selections, weights */

typedef struct msel {
    ms_atomset set;
    uint32_t *atoms;      /* owned */
    int molid;
    long frame;           /* -1: the molecule has no frames */
    const char *name;
} msel;

static void free_sel(msel *s)
{
    free(s->atoms);
    s->atoms = NULL;
}

/* Resolve a selection word; with need_frame, its molecule must have coordinates. */
static int get_sel(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, const char *cmd,
                   int need_frame, msel *s)
{
    size_t n = 0;
    memset(s, 0, sizeof *s);
    s->name = Tcl_GetString(word);
    if (ms_atomsel_resolve(app, interp, s->name, cmd, &s->molid, &s->frame, &s->atoms, &n) !=
        TCL_OK)
        return TCL_ERROR;
    ms_molecule *m = ms_molset_get(&app->mols, s->molid);
    if (!m || (need_frame && (s->frame < 0 || (size_t)s->frame >= m->nframes))) {
        free_sel(s);
        return ms_cmd_error(interp, "%s: %s: molecule %d has no coordinates", cmd, s->name,
                            s->molid);
    }
    s->set = (ms_atomset){m, s->frame < 0 ? 0 : (size_t)s->frame, s->atoms, n};
    return TCL_OK;
}

/* A weight list: one value per selected atom, or per atom of the molecule. */
static int weights_from_list(Tcl_Interp *interp, const char *cmd, const msel *s, Tcl_Obj *obj,
                             double *w)
{
    ms_numlist l;
    if (ms_tcl_get_numlist(interp, obj, cmd, "weight", &l) != TCL_OK)
        return ms_cmd_error(interp, "%s: weight: expected none, a floating-point atom keyword "
                            "(mass, charge, beta, occupancy, radius, user...) or a list of "
                            "numbers, got '%s'", cmd, Tcl_GetString(obj));
    int rc = TCL_OK;
    if ((size_t)l.n == s->set.n) memcpy(w, l.v, s->set.n * sizeof *w);
    else if ((size_t)l.n == s->set.mol->atoms.n)
        for (size_t i = 0; i < s->set.n; i++) w[i] = l.v[s->atoms[i]];
    else
        rc = ms_cmd_error(interp, "%s: weight: %d values for %zu selected atoms (give one per "
                          "selected atom or one per atom of molecule %d)", cmd, l.n, s->set.n,
                          s->molid);
    ms_numlist_free(&l);
    return rc;
}

/* VMD's weight argument; *w is NULL for `none` (all 1), else malloc'd, one per atom. */
static int get_weights(Tcl_Interp *interp, const char *cmd, const msel *s, Tcl_Obj *obj,
                       double **w)
{
    *w = NULL;
    const char *word = obj ? Tcl_GetString(obj) : "none";
    if (ms_word_eq(word, "none")) return TCL_OK;
    if (ms_measure_is_atom_keyword(word) && !ms_measure_is_float_keyword(word))
        return ms_cmd_error(interp, "%s: weight: '%s' does not have floating-point values", cmd,
                            word);
    if (!(*w = ms_alloc_array(s->set.n, sizeof **w)))
        return ms_cmd_error(interp, "%s: out of memory for %zu weights", cmd, s->set.n);
    ms_error err = {{0}};
    int rc = TCL_OK;
    if (ms_measure_is_float_keyword(word)) {
        if (ms_measure_atom_values(&s->set, word, *w, &err))
            rc = ms_cmd_error(interp, "%s: weight: %s", cmd, err.msg);
    } else {
        rc = weights_from_list(interp, cmd, s, obj, *w);
    }
    if (rc != TCL_OK) {
        free(*w);
        *w = NULL;
    }
    return rc;
}

/* weight (and fit's order): each at most once */
typedef struct weight_args {
    Tcl_Obj *weight, *order;
} weight_args;

static const ms_opt weight_options[] = {
    {"weight", MS_OPT_OBJ, offsetof(weight_args, weight), 0, 0, MS_OPT_ONCE, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};
static const ms_opt fit_options[] = {
    {"weight", MS_OPT_OBJ, offsetof(weight_args, weight), 0, 0, MS_OPT_ONCE, NULL},
    {"order", MS_OPT_OBJ, offsetof(weight_args, order), 0, 0, MS_OPT_ONCE, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

/* The weight option from objv[at] on (NULL when not given). */
static int weight_option(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int at,
                         Tcl_Obj **wobj)
{
    weight_args a = {NULL, NULL};
    int rc = ms_args_options(interp, objc, objv, at, weight_options, &a, NULL);
    *wobj = a.weight;
    return rc;
}

/* "<sel> ?weight <w>?" at objv[2]: the selection (with coordinates) and its weights. */
static int sel_weighted(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[],
                        const char *cmd, msel *s, double **w)
{
    Tcl_Obj *wobj;
    if (weight_option(interp, objc, objv, 3, &wobj) != TCL_OK) return TCL_ERROR;
    if (get_sel(app, interp, objv[2], cmd, 1, s) != TCL_OK) return TCL_ERROR;
    if (get_weights(interp, cmd, s, wobj, w) == TCL_OK) return TCL_OK;
    free_sel(s);
    return TCL_ERROR;
}

static int core_error(Tcl_Interp *interp, const char *cmd, const ms_error *err)
{
    return ms_cmd_error(interp, "%s: %s", cmd, err->msg);
}

/* ---------------------------------------------------------------- one selection */

SUBCMD(m_center)
{
    const char *cmd = "measure center";
    msel s;
    double *w, c[3];
    ms_error err = {{0}};
    if (sel_weighted(app, interp, objc, objv, cmd, &s, &w) != TCL_OK) return TCL_ERROR;
    int rc = ms_measure_center(&s.set, w, c, &err) ? core_error(interp, cmd, &err) : TCL_OK;
    if (rc == TCL_OK) Tcl_SetObjResult(interp, ms_tcl_new_doubles(c, 3));
    free(w);
    free_sel(&s);
    return rc;
}

SUBCMD(m_sumweights)
{
    const char *cmd = "measure sumweights";
    msel s;
    double *w = NULL;
    Tcl_Obj *wobj;
    if (weight_option(interp, objc, objv, 3, &wobj) != TCL_OK) return TCL_ERROR;
    if (get_sel(app, interp, objv[2], cmd, 1, &s) != TCL_OK) return TCL_ERROR;
    int rc = get_weights(interp, cmd, &s, wobj, &w);
    if (rc == TCL_OK)
        Tcl_SetObjResult(interp, Tcl_NewDoubleObj(ms_measure_sumweights(w, s.set.n)));
    free(w);
    free_sel(&s);
    return rc;
}

SUBCMD(m_minmax)
{
    const char *cmd = "measure minmax";
    msel s;
    double lo[3], hi[3];
    ms_error err = {{0}};
    static const ms_opt options[] = {{"-withradii", MS_OPT_FLAG, 0, 0, 0, 0, NULL},
                                     {NULL, 0, 0, 0, 0, 0, NULL}};
    int radii = 0;
    if (ms_args_options(interp, objc, objv, 3, options, &radii, NULL)) return TCL_ERROR;
    if (get_sel(app, interp, objv[2], cmd, 1, &s) != TCL_OK) return TCL_ERROR;
    int rc = TCL_OK;
    if (ms_measure_minmax(&s.set, radii, lo, hi, &err)) rc = core_error(interp, cmd, &err);
    else {
        Tcl_Obj *box[2] = {ms_tcl_new_doubles(lo, 3), ms_tcl_new_doubles(hi, 3)};
        Tcl_SetObjResult(interp, Tcl_NewListObj(2, box));
    }
    free_sel(&s);
    return rc;
}

SUBCMD(m_rgyr)
{
    const char *cmd = "measure rgyr";
    msel s;
    double *w, r;
    ms_error err = {{0}};
    if (sel_weighted(app, interp, objc, objv, cmd, &s, &w) != TCL_OK) return TCL_ERROR;
    int rc = ms_measure_rgyr(&s.set, w, &r, &err) ? core_error(interp, cmd, &err) : TCL_OK;
    if (rc == TCL_OK) Tcl_SetObjResult(interp, Tcl_NewDoubleObj(r));
    free(w);
    free_sel(&s);
    return rc;
}

/* inertia: options moments and eigenvals, with or without a dash, in any order; the
 * answer always lists the tensor before the eigenvalues, as VMD's does. */
typedef struct inertia_args {
    int moments, eigen;
} inertia_args;

SUBCMD(m_inertia)
{
    static const ms_opt options[] = {
        {"-moments", MS_OPT_FLAG, offsetof(inertia_args, moments), 0, 0, 0, NULL},
        {"moments", MS_OPT_FLAG, offsetof(inertia_args, moments), 0, 0, MS_OPT_ALIAS, NULL},
        {"-eigenvals", MS_OPT_FLAG, offsetof(inertia_args, eigen), 0, 0, 0, NULL},
        {"eigenvals", MS_OPT_FLAG, offsetof(inertia_args, eigen), 0, 0, MS_OPT_ALIAS, NULL},
        {NULL, 0, 0, 0, 0, 0, NULL}};
    const char *cmd = "measure inertia";
    inertia_args a = {0, 0};
    msel s;
    ms_inertia in;
    ms_error err = {{0}};
    if (ms_args_options(interp, objc, objv, 3, options, &a, NULL)) return TCL_ERROR;
    int moments = a.moments, eigen = a.eigen;
    if (get_sel(app, interp, objv[2], cmd, 1, &s) != TCL_OK) return TCL_ERROR;
    int rc = ms_measure_inertia(&s.set, &in, &err) ? core_error(interp, cmd, &err) : TCL_OK;
    free_sel(&s);
    if (rc != TCL_OK) return rc;
    Tcl_Obj *res = Tcl_NewListObj(0, NULL), *axes = Tcl_NewListObj(0, NULL), *t = Tcl_NewListObj(0, NULL);
    Tcl_ListObjAppendElement(NULL, res, ms_tcl_new_doubles(in.com, 3));
    for (int k = 0; k < 3; k++) {
        Tcl_ListObjAppendElement(NULL, axes, ms_tcl_new_doubles(in.axes[k], 3));
        Tcl_ListObjAppendElement(NULL, t, ms_tcl_new_doubles(in.tensor[k], 3));
    }
    Tcl_ListObjAppendElement(NULL, res, axes);
    if (moments) Tcl_ListObjAppendElement(NULL, res, t);
    else Tcl_DecrRefCount(t);
    if (eigen) Tcl_ListObjAppendElement(NULL, res, ms_tcl_new_doubles(in.moments, 3));
    Tcl_SetObjResult(interp, res);
    return TCL_OK;
}

/* ---------------------------------------------------------------- two selections */

/* Two selections with coordinates and equally many atoms, at objv[2] and objv[3]. */
static int sel_pair(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[], const char *cmd,
                    msel *a, msel *b)
{
    if (get_sel(app, interp, objv[2], cmd, 1, a) != TCL_OK) return TCL_ERROR;
    if (get_sel(app, interp, objv[3], cmd, 1, b) != TCL_OK) {
        free_sel(a);
        return TCL_ERROR;
    }
    if (a->set.n == b->set.n && a->set.n > 0) return TCL_OK;
    int rc = a->set.n != b->set.n
                 ? ms_cmd_error(interp, "%s: selections must have the same number of atoms "
                                "(%s has %zu, %s has %zu)", cmd, a->name, a->set.n, b->name,
                                b->set.n)
                 : ms_cmd_error(interp, "%s: no atoms selected", cmd);
    free_sel(a);
    free_sel(b);
    return rc;
}

SUBCMD(m_rmsd)
{
    const char *cmd = "measure rmsd";
    msel a, b;
    double *w = NULL, r;
    ms_error err = {{0}};
    Tcl_Obj *wobj;
    if (weight_option(interp, objc, objv, 4, &wobj) != TCL_OK) return TCL_ERROR;
    if (sel_pair(app, interp, objv, cmd, &a, &b) != TCL_OK) return TCL_ERROR;
    int rc = get_weights(interp, cmd, &a, wobj, &w);
    if (rc == TCL_OK && ms_measure_rmsd(&a.set, &b.set, w, &r, &err))
        rc = core_error(interp, cmd, &err);
    if (rc == TCL_OK) Tcl_SetObjResult(interp, Tcl_NewDoubleObj(r));
    free(w);
    free_sel(&a);
    free_sel(&b);
    return rc;
}

/* fit's order list: n indices into sel2, each 0..n-1. */
static int get_order(Tcl_Interp *interp, Tcl_Obj *obj, size_t n, uint32_t **order)
{
    Tcl_Obj **e;
    int ne;
    if (Tcl_ListObjGetElements(NULL, obj, &ne, &e) != TCL_OK || (size_t)ne != n)
        return ms_cmd_error(interp, "measure fit: order: expected a list of %zu indices, got '%s'",
                            n, Tcl_GetString(obj));
    if (!(*order = ms_alloc_array(n, sizeof **order)))
        return ms_cmd_error(interp, "measure fit: out of memory");
    for (size_t i = 0; i < n; i++) {
        Tcl_WideInt v;
        if (Tcl_GetWideIntFromObj(NULL, e[i], &v) != TCL_OK || v < 0 || (size_t)v >= n) {
            free(*order);
            *order = NULL;
            return ms_cmd_error(interp, "measure fit: order: '%s' is not an index from 0 to %zu",
                                Tcl_GetString(e[i]), n - 1);
        }
        (*order)[i] = (uint32_t)v;
    }
    return TCL_OK;
}

SUBCMD(m_fit)
{
    const char *cmd = "measure fit";
    weight_args o = {NULL, NULL};
    msel a, b;
    double *w = NULL, m[16];
    uint32_t *order = NULL;
    ms_error err = {{0}};
    if (ms_args_options(interp, objc, objv, 4, fit_options, &o, NULL) != TCL_OK) return TCL_ERROR;
    Tcl_Obj *wobj = o.weight, *oobj = o.order;
    if (sel_pair(app, interp, objv, cmd, &a, &b) != TCL_OK) return TCL_ERROR;
    int rc = get_weights(interp, cmd, &a, wobj, &w);
    if (rc == TCL_OK && oobj) rc = get_order(interp, oobj, a.set.n, &order);
    if (rc == TCL_OK && ms_measure_fit(&a.set, &b.set, w, order, m, &err))
        rc = core_error(interp, cmd, &err);
    if (rc == TCL_OK) Tcl_SetObjResult(interp, ms_tcl_new_mat4(m));
    free(w);
    free(order);
    free_sel(&a);
    free_sel(&b);
    return rc;
}

/* ---------------------------------------------------------------- over frames */

/* first/last/step options, VMD's defaults 0, -1 (the last frame), 1. */
static const ms_opt frame_options[] = {
    {"first", MS_OPT_LONG, 0 * sizeof(long), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"last", MS_OPT_LONG, 1 * sizeof(long), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"step", MS_OPT_LONG, 2 * sizeof(long), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

/* avpos and rmsf: per-atom averages over the frames. */
static int per_atom_over_frames(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[],
                                const char *cmd, int rmsf)
{
    long fls[3];
    msel s;
    ms_frame_range r;
    ms_error err = {{0}};
    fls[0] = 0, fls[1] = -1, fls[2] = 1;
    if (ms_args_options(interp, objc, objv, 3, frame_options, fls, NULL) != TCL_OK) return TCL_ERROR;
    if (get_sel(app, interp, objv[2], cmd, 0, &s) != TCL_OK) return TCL_ERROR;
    double *out = ms_alloc_array(s.set.n, (rmsf ? 1 : 3) * sizeof *out);
    int rc = TCL_OK;
    if (!out) rc = ms_cmd_error(interp, "%s: out of memory", cmd);
    else if (ms_frame_range_make(s.set.mol, fls[0], fls[1], fls[2], &r, &err) ||
             (rmsf ? ms_measure_rmsf(s.set.mol, s.atoms, s.set.n, &r, out, &err)
                   : ms_measure_avpos(s.set.mol, s.atoms, s.set.n, &r, out, &err)))
        rc = core_error(interp, cmd, &err);
    else if (rmsf) Tcl_SetObjResult(interp, ms_tcl_new_doubles(out, (int)s.set.n));
    else {
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (size_t i = 0; i < s.set.n; i++)
            Tcl_ListObjAppendElement(NULL, l, ms_tcl_new_doubles(out + 3 * i, 3));
        Tcl_SetObjResult(interp, l);
    }
    free(out);
    free_sel(&s);
    return rc;
}

SUBCMD(m_avpos) { return per_atom_over_frames(app, interp, objc, objv, "measure avpos", 0); }
SUBCMD(m_rmsf) { return per_atom_over_frames(app, interp, objc, objv, "measure rmsf", 1); }

/* ---------------------------------------------------------------- pairs */

static Tcl_Obj *index_list(const uint32_t *v, size_t n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < n; i++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewWideIntObj(v[i]));
    return l;
}

/* One or two selections from objv[at]; b is a copy of a when the second is missing. */
static int one_or_two(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int at,
                      const char *cmd, msel *a, msel *b, int *two)
{
    *two = objc == at + 2;
    if (get_sel(app, interp, objv[at], cmd, 1, a) != TCL_OK) return TCL_ERROR;
    if (*two && get_sel(app, interp, objv[at + 1], cmd, 1, b) != TCL_OK) {
        free_sel(a);
        return TCL_ERROR;
    }
    if (!*two) *b = *a, b->atoms = NULL;   /* shares a's atoms, owns nothing */
    return TCL_OK;
}

SUBCMD(m_contacts)
{
    const char *cmd = "measure contacts";
    double cutoff;
    msel a, b;
    int two;
    ms_pairs p;
    ms_error err = {{0}};
    if (ms_arg_double(interp, objv[2], "cutoff", &cutoff) != TCL_OK) return TCL_ERROR;
    if (one_or_two(app, interp, objc, objv, 3, cmd, &a, &b, &two) != TCL_OK) return TCL_ERROR;
    int rc = TCL_OK;
    if (ms_measure_contacts(&a.set, two ? &b.set : NULL, cutoff, &p, &err))
        rc = core_error(interp, cmd, &err);
    else {
        Tcl_Obj *l[2] = {index_list(p.a, p.n), index_list(p.b, p.n)};
        Tcl_SetObjResult(interp, Tcl_NewListObj(2, l));
        ms_pairs_free(&p);
    }
    free_sel(&a);
    free_sel(&b);
    return rc;
}

SUBCMD(m_hbonds)
{
    const char *cmd = "measure hbonds";
    double cutoff, angle;
    msel a, b;
    int two;
    ms_hbonds h;
    ms_error err = {{0}};
    if (ms_arg_double(interp, objv[2], "cutoff", &cutoff) != TCL_OK ||
        ms_arg_double(interp, objv[3], "angle", &angle) != TCL_OK)
        return TCL_ERROR;
    if (one_or_two(app, interp, objc, objv, 4, cmd, &a, &b, &two) != TCL_OK) return TCL_ERROR;
    int rc = TCL_OK;
    if (two && a.molid != b.molid)
        rc = ms_cmd_error(interp, "%s: atom selections must come from the same molecule", cmd);
    else if (ms_measure_hbonds(&a.set, two ? &b.set : NULL, cutoff, angle, &h, &err))
        rc = core_error(interp, cmd, &err);
    else {
        Tcl_Obj *l[3] = {index_list(h.donor, h.n), index_list(h.acceptor, h.n),
                         index_list(h.hydrogen, h.n)};
        Tcl_SetObjResult(interp, Tcl_NewListObj(3, l));
        ms_hbonds_free(&h);
    }
    free_sel(&a);
    free_sel(&b);
    return rc;
}

/* ---------------------------------------------------------------- sasa */

typedef struct sasa_args {
    Tcl_Obj *points_var, *restrict_sel;
    int samples;
} sasa_args;

static const ms_opt sasa_options[] = {
    {"-points", MS_OPT_OBJ, offsetof(sasa_args, points_var), 0, 0, 0, NULL},
    {"-restrict", MS_OPT_OBJ, offsetof(sasa_args, restrict_sel), 0, 0, 0, NULL},
    {"-samples", MS_OPT_INT, offsetof(sasa_args, samples), 1, 10000000,
     MS_OPT_MIN | MS_OPT_MAX, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

/* Store the exposed points in the caller's variable as {{x y z} ...}. */
static int set_points(Tcl_Interp *interp, Tcl_Obj *var, const float *pts, size_t n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < n; i++) {
        double p[3] = {pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]};
        Tcl_ListObjAppendElement(NULL, l, ms_tcl_new_doubles(p, 3));
    }
    if (!Tcl_ObjSetVar2(interp, var, NULL, l, TCL_LEAVE_ERR_MSG)) return TCL_ERROR;
    return TCL_OK;
}

SUBCMD(m_sasa)
{
    const char *cmd = "measure sasa";
    sasa_args o;
    double srad, area;
    msel s, r = {0};
    float *pts = NULL;
    size_t npts = 0;
    ms_error err = {{0}};
    o = (sasa_args){NULL, NULL, 500};
    if (ms_arg_double(interp, objv[2], "probe radius", &srad) != TCL_OK ||
        ms_args_options(interp, objc, objv, 4, sasa_options, &o, NULL) != TCL_OK)
        return TCL_ERROR;
    if (get_sel(app, interp, objv[3], cmd, 1, &s) != TCL_OK) return TCL_ERROR;
    int rc = TCL_OK;
    if (o.restrict_sel && (rc = get_sel(app, interp, o.restrict_sel, cmd, 0, &r)) == TCL_OK &&
        r.molid != s.molid)
        rc = ms_cmd_error(interp, "%s: -restrict selection %s is not of molecule %d", cmd, r.name,
                          s.molid);
    ms_sasa_opts so = {srad, o.samples, r.atoms, r.set.n, o.points_var != NULL};
    if (rc == TCL_OK && ms_measure_sasa(&s.set, &so, &area, &pts, &npts, &err))
        rc = core_error(interp, cmd, &err);
    if (rc == TCL_OK && o.points_var) rc = set_points(interp, o.points_var, pts, npts);
    if (rc == TCL_OK) Tcl_SetObjResult(interp, Tcl_NewDoubleObj(area));
    free(pts);
    free_sel(&s);
    free_sel(&r);
    return rc;
}

/* ---------------------------------------------------------------- gofr */

typedef struct gofr_args {
    double delta, rmax;
    int usepbc, selupdate;
    long first, last, step;
} gofr_args;

#define GOFF(f) offsetof(gofr_args, f)
static const ms_opt gofr_options[] = {
    {"delta", MS_OPT_DOUBLE, GOFF(delta), 0, 0, MS_OPT_ABOVE, NULL},
    {"rmax", MS_OPT_DOUBLE, GOFF(rmax), 0, 0, MS_OPT_ABOVE, NULL},
    {"usepbc", MS_OPT_BOOL, GOFF(usepbc), 0, 0, 0, NULL},
    {"selupdate", MS_OPT_BOOL, GOFF(selupdate), 0, 0, 0, NULL},
    {"first", MS_OPT_LONG, GOFF(first), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"last", MS_OPT_LONG, GOFF(last), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"step", MS_OPT_LONG, GOFF(step), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

/* VMD's frame range: last -1 is the last frame; first -1 (the default) means the frame the
 * selections are on, alone. */
static int gofr_frames(Tcl_Interp *interp, const char *cmd, const ms_molecule *m, gofr_args *g)
{
    long max = (long)m->nframes - 1;
    if (g->last == -1) g->last = max;
    if (g->last < g->first || g->last < 0 || g->step <= 0 || g->first < -1 || max < 0 ||
        g->last > max)
        return ms_cmd_error(interp, "%s: bad frame range %ld to %ld step %ld (molecule %d has "
                            "%zu frames)", cmd, g->first, g->last, g->step, m->id, m->nframes);
    return TCL_OK;
}

/* selupdate: put a selection on a frame, re-evaluate it (`sel frame f; sel update`) and
 * resolve it again. */
static int sel_to_frame(ms_app *app, Tcl_Interp *interp, msel *s, Tcl_Obj *frame,
                        const char *cmd)
{
    const char *name = s->name;   /* points into the command's own words */
    Tcl_Obj *w[4] = {Tcl_NewStringObj(name, -1), Tcl_NewStringObj("frame", -1), frame,
                     Tcl_NewStringObj("update", -1)};
    for (int k = 0; k < 4; k++) Tcl_IncrRefCount(w[k]);
    int rc = Tcl_EvalObjv(interp, 3, w, 0);
    Tcl_Obj *upd[2] = {w[0], w[3]};
    if (rc == TCL_OK) rc = Tcl_EvalObjv(interp, 2, upd, 0);
    if (rc == TCL_OK) {
        free_sel(s);
        rc = get_sel(app, interp, w[0], cmd, 1, s);
    }
    s->name = name;
    for (int k = 0; k < 4; k++) Tcl_DecrRefCount(w[k]);
    return rc;
}

/* The selection's own frame word (`sel frame`), to put it back afterwards. */
static Tcl_Obj *sel_frame_word(Tcl_Interp *interp, const msel *s)
{
    Tcl_Obj *w[2] = {Tcl_NewStringObj(s->name, -1), Tcl_NewStringObj("frame", -1)}, *r = NULL;
    Tcl_IncrRefCount(w[0]);
    Tcl_IncrRefCount(w[1]);
    if (Tcl_EvalObjv(interp, 2, w, 0) == TCL_OK) Tcl_IncrRefCount(r = Tcl_GetObjResult(interp));
    Tcl_DecrRefCount(w[0]);
    Tcl_DecrRefCount(w[1]);
    return r;
}

/* Put selupdate's selections back on their frames, keeping the interpreter's result. */
static void restore_frames(ms_app *app, Tcl_Interp *interp, msel *s, Tcl_Obj **orig, int n,
                           const char *cmd)
{
    Tcl_Obj *result = Tcl_GetObjResult(interp);
    Tcl_IncrRefCount(result);
    for (int k = 0; k < n; k++)
        if (orig[k]) {
            sel_to_frame(app, interp, &s[k], orig[k], cmd);
            Tcl_DecrRefCount(orig[k]);
        }
    Tcl_SetObjResult(interp, result);
    Tcl_DecrRefCount(result);
}

/* Add the frames to the accumulator, moving the selections along with selupdate. */
static int gofr_run(ms_app *app, Tcl_Interp *interp, const char *cmd, msel s[2],
                    const gofr_args *g, ms_gofr *acc)
{
    ms_error err = {{0}};
    long first = g->first == -1 ? s[0].frame : g->first;
    long last = g->first == -1 ? s[0].frame : g->last;
    for (long f = first; f <= last; f += g->step) {
        for (int k = 0; k < 2 && g->selupdate; k++) {
            Tcl_Obj *fo = Tcl_NewWideIntObj(f);
            Tcl_IncrRefCount(fo);
            int rc = sel_to_frame(app, interp, &s[k], fo, cmd);
            Tcl_DecrRefCount(fo);
            if (rc != TCL_OK) return TCL_ERROR;
        }
        if (ms_gofr_add_frame(acc, s[0].set.mol, (size_t)f, s[0].atoms, s[0].set.n, s[1].atoms,
                              s[1].set.n, &err))
            return core_error(interp, cmd, &err);
    }
    return TCL_OK;
}

static Tcl_Obj *gofr_result(ms_gofr *acc)
{
    ms_gofr_result r;
    ms_gofr_get(acc, &r);
    Tcl_Obj *frames[3] = {Tcl_NewWideIntObj(r.frames_total), Tcl_NewWideIntObj(r.frames_skipped),
                          Tcl_NewWideIntObj(r.frames_done)};
    Tcl_Obj *l[5] = {ms_tcl_new_doubles(r.r, (int)r.nbins), ms_tcl_new_doubles(r.gofr, (int)r.nbins),
                     ms_tcl_new_doubles(r.numint, (int)r.nbins),
                     ms_tcl_new_doubles(r.hist, (int)r.nbins), Tcl_NewListObj(3, frames)};
    return Tcl_NewListObj(5, l);
}

static int gofr_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[],
                    const char *cmd)
{
    gofr_args g;
    msel s[2];
    Tcl_Obj *orig[2] = {NULL, NULL};
    ms_error err = {{0}};
    g = (gofr_args){0.1, 10.0, 0, 0, -1, -1, 1};
    if (ms_args_options(interp, objc, objv, 4, gofr_options, &g, NULL) != TCL_OK) return TCL_ERROR;
    if (get_sel(app, interp, objv[2], cmd, 1, &s[0]) != TCL_OK) return TCL_ERROR;
    if (get_sel(app, interp, objv[3], cmd, 1, &s[1]) != TCL_OK) {
        free_sel(&s[0]);
        return TCL_ERROR;
    }
    ms_gofr *acc = NULL;
    int rc = TCL_ERROR;
    if (s[0].molid != s[1].molid)
        ms_cmd_error(interp, "%s: both selections must reference the same molecule", cmd);
    else if (gofr_frames(interp, cmd, s[0].set.mol, &g) == TCL_OK &&
             !(acc = ms_gofr_new(g.delta, g.rmax, g.usepbc, &err)))
        core_error(interp, cmd, &err);
    else if (acc) {
        for (int k = 0; k < 2 && g.selupdate; k++) orig[k] = sel_frame_word(interp, &s[k]);
        rc = gofr_run(app, interp, cmd, s, &g, acc);
        if (g.selupdate) restore_frames(app, interp, s, orig, 2, cmd);
        if (rc == TCL_OK) Tcl_SetObjResult(interp, gofr_result(acc));
    }
    ms_gofr_free(acc);
    free_sel(&s[0]);
    free_sel(&s[1]);
    return rc;
}

SUBCMD(m_gofr) { return gofr_cmd(app, interp, objc, objv, "measure gofr"); }
SUBCMD(m_rdf) { return gofr_cmd(app, interp, objc, objv, "measure rdf"); }

void ms_cmd_measure_register(ms_app *app)
{
#define FRAMES_USAGE "<sel> ?first <f>? ?last <l>? ?step <s>?"
#define GOFR_USAGE                                                                        \
    "<sel1> <sel2> ?delta <d>? ?rmax <r>? ?usepbc <bool>? ?selupdate <bool>? ?first <f>? " \
    "?last <l>? ?step <s>?"
    static const ms_subcmd table[] = {
        {"avpos", m_avpos, 1, MS_ARGS_ANY, FRAMES_USAGE},
        {"center", m_center, 1, 3, "<sel> ?weight <w>?"},
        {"contacts", m_contacts, 2, 3, "<cutoff> <sel1> ?<sel2>?"},
        {"fit", m_fit, 2, 6, "<sel1> <sel2> ?weight <w>? ?order <index list>?"},
        {"gofr", m_gofr, 2, MS_ARGS_ANY, GOFR_USAGE},
        {"hbonds", m_hbonds, 3, 4, "<cutoff> <angle> <sel1> ?<sel2>?"},
        {"inertia", m_inertia, 1, 3, "<sel> ?-moments? ?-eigenvals?"},
        {"minmax", m_minmax, 1, 2, "<sel> ?-withradii?"},
        {"rdf", m_rdf, 2, MS_ARGS_ANY, GOFR_USAGE},
        {"rgyr", m_rgyr, 1, 3, "<sel> ?weight <w>?"},
        {"rmsd", m_rmsd, 2, 4, "<sel1> <sel2> ?weight <w>?"},
        {"rmsf", m_rmsf, 1, MS_ARGS_ANY, FRAMES_USAGE},
        {"sasa", m_sasa, 2, MS_ARGS_ANY,
         "<srad> <sel> ?-points <var>? ?-restrict <sel>? ?-samples <n>?"},
        {"sumweights", m_sumweights, 3, 3, "<sel> weight <w>"},
        {NULL, NULL, 0, 0, NULL}};
    ms_cmdset_create(app, "measure", table);
    ms_cmdset_quiet(app, "measure");
}
