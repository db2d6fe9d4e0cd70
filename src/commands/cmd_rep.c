/* cmd_rep.c: the representation subcommands of `mol` and molinfo's rep keywords, with VMD's
 * argument orders (modstyle, modselect, modcolor, modmaterial, modrep, delrep, selupdate and
 * colupdate take <repid> <molid>; showrep, drawframes, smoothrep, scaleminmax, showperiodic,
 * numperiodic, repname and repindex take <molid> <repid>):
 *
 *   mol representation|rep ?style...?   mol selection ?text...?   mol color ?method...?
 *   mol material ?name?                 (set the current settings; with no value, get them)
 *   mol addrep molid                    mol modrep repid molid      mol delrep repid molid
 *   mol modstyle|modselect|modcolor|modmaterial repid molid value...
 *   mol showrep molid repid ?on|off?    mol drawframes molid repid ?spec|now?
 *   mol smoothrep molid repid ?n?       mol scaleminmax molid repid ?min max|auto?
 *   mol showperiodic molid repid ?xyzXYZn?   mol numperiodic molid repid ?n?
 *   mol selupdate|colupdate repid molid ?on|off?
 *   mol repname molid repid             mol repindex molid name      (-1 when none)
 *   mol default color|style|selection|material ?value?
 *   mol clipplane center|normal|color clipid repid molid ?{x y z}?
 *   mol clipplane status clipid repid molid ?0|1|2?     mol clipplane num      (6)
 *   mol repinfo molid repid ?kind?      (molscope: what a rep draws, for tests and scripts)
 *   molinfo <molid> get {numreps "rep i" "selection i" "color i" "material i"}
 *
 * A new structure loaded by mol new / mol addfile resets the current settings to the
 * defaults and gets one rep made from them (VMD's rule); a molecule of volumetric data
 * alone gets an Isosurface rep (rep/rep.c does both, hearing the molecule set's load
 * events). Every error names the command and the bad value, and changes nothing. */
#include "config.h"
#include "commands/commands.h"
#include "commands/molinfo.h"
#include "rep/rep.h"
#include "scene/material.h"

#include <limits.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A rep id as VMD reads one: the leading integer of the word, 0 when there is none
 * (`mol modstyle top 0 ...` has "top" where a rep id goes). */
static long rep_number(Tcl_Obj *w)
{
    long id;
    if (Tcl_GetLongFromObj(NULL, w, &id) == TCL_OK) return id;
    return strtol(Tcl_GetString(w), NULL, 10);
}

/* Rep `w` of molecule m; NULL with an error naming cmd, the word and the molecule. */
static ms_rep *get_rep(ms_app *app, Tcl_Interp *interp, ms_molecule *m, Tcl_Obj *w, const char *cmd,
                       long *repid)
{
    long id = rep_number(w);
    ms_rep *r = ms_rep_get(app->world.reps, m, id);
    if (!r)
        ms_cmd_error(interp, "%s: molecule %d has no rep %ld (it has %zu)", cmd, m->id, id,
                     ms_rep_count(app->world.reps, m));
    if (repid) *repid = id;
    return r;
}

/* The molecule and rep of "<repid> <molid>" (rep_first) or "<molid> <repid>" at objv[2..3]. */
static ms_rep *target(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[], int rep_first,
                      const char *cmd, ms_molecule **mp, long *repid)
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[rep_first ? 3 : 2], cmd);
    if (!m) return NULL;
    if (mp) *mp = m;
    return get_rep(app, interp, m, objv[rep_first ? 2 : 3], cmd, repid);
}

/* The same for the commands VMD lets through when the rep does not exist (modstyle,
 * modselect, modcolor, modmaterial, modrep, delrep): NULL with *skip set and no error then. */
static ms_rep *lenient_target(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[],
                              const char *cmd, ms_molecule **mp, long *repid, int *skip)
{
    *skip = 0;
    ms_molecule *m = ms_cmd_mol(app, interp, objv[3], cmd);
    if (!m) return NULL;
    *mp = m;
    long id = rep_number(objv[2]);
    if (repid) *repid = id;
    ms_rep *r = ms_rep_get(app->world.reps, m, id);
    *skip = r == NULL;
    return r;
}

/* The words that name what of a rep a subcommand or keyword is about. */
static const struct {
    const char *name;
    ms_rep_what what;
} what_words[] = {
    {"representation", MS_REP_STYLE}, {"rep", MS_REP_STYLE}, {"style", MS_REP_STYLE},
    {"modstyle", MS_REP_STYLE}, {"selection", MS_REP_SELECTION},
    {"modselect", MS_REP_SELECTION}, {"color", MS_REP_COLOR}, {"modcolor", MS_REP_COLOR},
    {"material", MS_REP_MATERIAL}, {"modmaterial", MS_REP_MATERIAL}, {NULL, MS_REP_STYLE}};

static int what_of(const char *w, ms_rep_what *what)
{
    int k = ms_args_find(what_words, sizeof *what_words, w);
    if (k < 0) return -1;
    *what = what_words[k].what;
    return 0;
}

/* ---------------------------------------------------------------- current settings */

/* mol representation|rep|selection|color|material ?value...? */
static int m_current(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = ms_args_where();
    ms_rep_what what = MS_REP_STYLE;
    what_of(Tcl_GetString(objv[1]), &what);
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_rep_text(app->world.reps, NULL, what), -1));
        return TCL_OK;
    }
    Tcl_Obj *text = ms_args_joined(objc, objv, 2);
    Tcl_IncrRefCount(text);
    ms_error err = {{0}};
    int rc = ms_rep_set_current(app->world.reps, what, Tcl_GetString(text), &err);
    Tcl_DecrRefCount(text);
    return rc ? ms_cmd_error(interp, "%s: %s", cmd, err.msg) : TCL_OK;
}

/* mol default color|style|representation|selection|material ?value? */
static int m_default(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    /* every word of what_words is taken; a refused one is told the usual four */
    static const char *const words[] = {"color", "style", "selection", "material", NULL};
    ms_rep_what what = MS_REP_STYLE;
    int k;
    if (what_of(Tcl_GetString(objv[2]), &what))
        return ms_arg_choice(interp, objv[2], words, NULL, &k);
    if (objc == 3) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_rep_get_default(app->world.reps, what), -1));
        return TCL_OK;
    }
    ms_error err = {{0}};
    if (ms_rep_set_default(app->world.reps, what, Tcl_GetString(objv[3]), &err))
        return ms_cmd_error(interp, "mol default %s: %s", Tcl_GetString(objv[2]), err.msg);
    return TCL_OK;
}

/* ---------------------------------------------------------------- adding and editing */

/* As VMD, a rep's selection and colours are evaluated when they are set (so a coordinate
 * selection or a colour range comes from the frame current then). */
static int settle(ms_app *app, Tcl_Interp *interp, ms_molecule *m, ms_rep *r, const char *cmd)
{
    ms_error err = {{0}};
    if (m->nframes && ms_rep_update_data(app->world.reps, m, r, &err))
        return ms_cmd_error(interp, "%s: %s", cmd, err.msg);
    return TCL_OK;
}

static int m_addrep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], "mol addrep");
    if (!m) return TCL_ERROR;
    ms_error err = {{0}};
    ms_rep *r = ms_rep_add(app->world.reps, m, &err);
    if (!r) return ms_cmd_error(interp, "mol addrep: %s", err.msg);
    return settle(app, interp, m, r, "mol addrep");
}

static int m_delrep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m;
    long id;
    int skip;
    if (!lenient_target(app, interp, objv, "mol delrep", &m, &id, &skip)) return skip ? TCL_OK : TCL_ERROR;
    ms_rep_delete(app->world.reps, m, (size_t)id);
    return TCL_OK;
}

static int m_modrep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m;
    int skip;
    ms_rep *r = lenient_target(app, interp, objv, "mol modrep", &m, NULL, &skip);
    ms_error err = {{0}};
    if (!r) return skip ? TCL_OK : TCL_ERROR;
    if (ms_rep_apply_current(app->world.reps, m, r, &err)) return ms_cmd_error(interp, "mol modrep: %s", err.msg);
    return settle(app, interp, m, r, "mol modrep");
}

/* mol modstyle|modselect|modcolor|modmaterial <repid> <molid> <value...> */
static int m_modify(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = ms_args_where();
    ms_rep_what what = MS_REP_STYLE;
    what_of(Tcl_GetString(objv[1]), &what);
    ms_molecule *m;
    int skip;
    ms_rep *r = lenient_target(app, interp, objv, cmd, &m, NULL, &skip);
    if (!r) return skip ? TCL_OK : TCL_ERROR;
    Tcl_Obj *text = ms_args_joined(objc, objv, 4);
    Tcl_IncrRefCount(text);
    ms_error err = {{0}};
    int rc = ms_rep_modify(app->world.reps, m, r, what, Tcl_GetString(text), &err);
    Tcl_DecrRefCount(text);
    if (rc) return ms_cmd_error(interp, "%s: %s", cmd, err.msg);
    return what == MS_REP_SELECTION || what == MS_REP_COLOR ? settle(app, interp, m, r, cmd) : TCL_OK;
}

/* ---------------------------------------------------------------- per-rep switches */

/* mol showrep <molid> <repid> ?bool?; mol selupdate|colupdate <repid> <molid> ?bool? */
static int m_flag(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    int show = ms_word_eq(w, "showrep"), sel = ms_word_eq(w, "selupdate");
    ms_rep *r = target(app, interp, objv, !show, ms_args_where(), NULL, NULL);
    if (!r) return TCL_ERROR;
    int *flag = show ? &r->shown : sel ? &r->selupdate : &r->colupdate, v;
    if (objc == 4) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(*flag));
        return TCL_OK;
    }
    if (ms_arg_bool(interp, objv[4], NULL, &v)) return TCL_ERROR;
    *flag = v;
    return TCL_OK;
}

static int m_drawframes(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_rep *r = target(app, interp, objv, 0, "mol drawframes", NULL, NULL);
    if (!r) return TCL_ERROR;
    if (objc == 4) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(r->frames, -1));
        return TCL_OK;
    }
    Tcl_Obj *spec = ms_args_joined(objc, objv, 4);
    Tcl_IncrRefCount(spec);
    ms_error err = {{0}};
    int rc = ms_rep_set_frames(r, Tcl_GetString(spec), &err);
    Tcl_DecrRefCount(spec);
    return rc ? ms_cmd_error(interp, "mol drawframes: %s", err.msg) : TCL_OK;
}

static int m_smoothrep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_rep *r = target(app, interp, objv, 0, "mol smoothrep", NULL, NULL);
    if (!r) return TCL_ERROR;
    if (objc == 4) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(r->smooth));
        return TCL_OK;
    }
    long n;
    if (ms_arg_long(interp, objv[4], NULL, 0, 100000, &n)) return TCL_ERROR;
    ms_rep_set_smooth(r, (int)n);
    return TCL_OK;
}

static int m_scaleminmax(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m;
    ms_rep *r = target(app, interp, objv, 0, "mol scaleminmax", &m, NULL);
    if (!r) return TCL_ERROR;
    if (objc == 4) {
        ms_error err = {{0}};
        if (ms_rep_update_data(app->world.reps, m, r, &err))
            return ms_cmd_error(interp, "mol scaleminmax: %s", err.msg);
        Tcl_SetObjResult(interp, Tcl_ObjPrintf("%f %f", r->cmin, r->cmax));
        return TCL_OK;
    }
    if (objc == 5) {
        static const char *const auto_word[] = {"auto", NULL};
        int k;
        if (ms_arg_choice(interp, objv[4], auto_word, NULL, &k)) return TCL_ERROR;
        ms_rep_auto_range(r);
        return TCL_OK;
    }
    double lo, hi;
    if (ms_arg_double(interp, objv[4], "min", &lo) || ms_arg_double(interp, objv[5], "max", &hi))
        return TCL_ERROR;
    ms_rep_set_range(r, (float)lo, (float)hi);
    return TCL_OK;
}

/* ---------------------------------------------------------------- periodic images */

/* mol showperiodic <molid> <repid> ?flags?; mol numperiodic <molid> <repid> ?n? */
static int m_periodic(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = ms_args_where();
    char text[8];
    int num = ms_word_eq(Tcl_GetString(objv[1]), "numperiodic"), rc;
    ms_rep *r = target(app, interp, objv, 0, cmd, NULL, NULL);
    if (!r) return TCL_ERROR;
    if (objc == 4) {
        ms_rep_periodic_text(r, text);
        Tcl_SetObjResult(interp, num ? Tcl_NewIntObj(r->npbc) : Tcl_NewStringObj(text, -1));
        return TCL_OK;
    }
    ms_error err = {{0}};
    long n;
    if (!num) rc = ms_rep_set_periodic(r, Tcl_GetString(objv[4]), &err);
    else if (ms_arg_long(interp, objv[4], NULL, LONG_MIN, LONG_MAX, &n)) return TCL_ERROR;
    else rc = ms_rep_set_numperiodic(r, n, &err);
    return rc ? ms_cmd_error(interp, "%s: %s", cmd, err.msg) : TCL_OK;
}

/* ---------------------------------------------------------------- clip planes */

/* The plane of "<clipid> <repid> <molid>" at objv[3..5]. */
static ms_clip *clip_target(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[])
{
    const char *cmd = ms_args_where();
    int k;
    ms_molecule *m = ms_cmd_mol(app, interp, objv[5], cmd);
    if (!m || ms_arg_int(interp, objv[3], "clipid", 0, MS_SCENE_CLIPS - 1, &k)) return NULL;
    ms_rep *r = get_rep(app, interp, m, objv[4], cmd, NULL);
    return r ? &r->clip[k] : NULL;
}

static Tcl_Obj *vec_obj(const float v[3])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < 3; i++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewDoubleObj(v[i]));
    return l;
}

/* mol clipplane center|normal|color <clipid> <repid> <molid> ?{x y z}? */
static int clip_vector(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_clip *c = clip_target(app, interp, objv);
    if (!c) return TCL_ERROR;
    const char *w = Tcl_GetString(objv[2]);
    float *v = ms_word_eq(w, "center") ? c->center : ms_word_eq(w, "normal") ? c->normal : c->color;
    if (objc == 6) {
        Tcl_SetObjResult(interp, vec_obj(v));
        return TCL_OK;
    }
    float in[3];
    if (ms_arg_vec3(interp, objv[6], w, in)) return TCL_ERROR;
    if (v == c->normal && in[0] == 0 && in[1] == 0 && in[2] == 0)
        return ms_cmd_error(interp, "%s: the normal {0 0 0} has no direction", ms_args_where());
    if (v == c->color)
        for (int i = 0; i < 3; i++) in[i] = MS_MIN(1.0f, MS_MAX(0.0f, in[i]));
    memcpy(v, in, sizeof in);
    return TCL_OK;
}

/* mol clipplane status <clipid> <repid> <molid> ?0|1|2? */
static int clip_status(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_clip *c = clip_target(app, interp, objv);
    if (!c) return TCL_ERROR;
    if (objc == 6) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(c->mode));
        return TCL_OK;
    }
    return ms_arg_int(interp, objv[6], "status", MS_CLIP_OFF, MS_CLIP_SOLID, &c->mode);
}

static int clip_num(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(MS_SCENE_CLIPS));
    return TCL_OK;
}

static int m_clipplane(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd table[] = {
        {"center", clip_vector, 3, 4, "<clipid> <repid> <molid> ?{x y z}?"},
        {"normal", clip_vector, 3, 4, "<clipid> <repid> <molid> ?{x y z}?"},
        {"color", clip_vector, 3, 4, "<clipid> <repid> <molid> ?{r g b}?"},
        {"status", clip_status, 3, 4, "<clipid> <repid> <molid> ?0|1|2?"},
        {"num", clip_num, 0, 0, ""},
        {NULL, NULL, 0, 0, NULL}};
    return ms_args_dispatch(app, interp, objc, objv, 2, table, NULL, "mol clipplane");
}

/* ---------------------------------------------------------------- names */

static int m_repname(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_rep *r = target(app, interp, objv, 0, "mol repname", NULL, NULL);
    if (!r) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewStringObj(r->name, -1));
    return TCL_OK;
}

static int m_repindex(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], "mol repindex");
    if (!m) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewLongObj(ms_rep_find(app->world.reps, m, Tcl_GetString(objv[3]))));
    return TCL_OK;
}

/* ---------------------------------------------------------------- repinfo */

static Tcl_Obj *floats(const float *v, int n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < n; i++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewDoubleObj(v[i]));
    return l;
}

static void add_rgb(Tcl_Obj *l, ms_rgba8 c)
{
    Tcl_ListObjAppendElement(NULL, l, Tcl_NewIntObj(c.r));
    Tcl_ListObjAppendElement(NULL, l, Tcl_NewIntObj(c.g));
    Tcl_ListObjAppendElement(NULL, l, Tcl_NewIntObj(c.b));
}

static Tcl_Obj *counts(ms_app *app, const ms_rep *r)
{
    const ms_displaylist *dl = ms_rep_list(r);
    size_t natoms;
    ms_rep_atoms(r, &natoms);
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    const struct {
        const char *k;
        size_t v;
    } c[] = {{"spheres", dl->spheres.n}, {"cylinders", ms_dl_piece_count(&dl->cylinders)}, {"cones", dl->cones.n},
             {"lines", dl->lines.n}, {"points", dl->points.n}, {"triangles", dl->mesh.ntris},
             {"vertices", dl->mesh.nverts}, {"atoms", natoms}, {"builds", ms_rep_builds(r)},
             {"lit", (size_t)dl->lit}};
    for (size_t i = 0; i < MS_COUNTOF(c); i++) {
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(c[i].k, -1));
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewWideIntObj((Tcl_WideInt)c[i].v));
    }
    Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj("material", -1));
    Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_material_by_id(app->world.materials, r->material)->name, -1));
    return l;
}

/* One cylinder piece (a plain cylinder, or half a bond) as a flat list of numbers. */
static Tcl_Obj *piece(const ms_dl_piece *p)
{
    Tcl_Obj *e = floats(p->a, 3);
    Tcl_ListObjAppendList(NULL, e, floats(p->b, 3));
    Tcl_ListObjAppendElement(NULL, e, Tcl_NewDoubleObj(p->radius));
    add_rgb(e, p->color);
    Tcl_ListObjAppendElement(NULL, e, Tcl_NewIntObj(p->res));
    return e;
}

/* One primitive of a kind (not cylinders) as a flat list of numbers. */
static Tcl_Obj *primitive(const ms_displaylist *dl, int kind, size_t i)
{
    Tcl_Obj *e;
    switch (kind) {
    case 0:
        e = floats(dl->spheres.xyz + 3 * i, 3);
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewDoubleObj(dl->spheres.radius[i]));
        add_rgb(e, dl->spheres.color[i]);
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewIntObj(dl->spheres.res[i]));
        return e;
    case 2:
        e = floats(dl->lines.a + 3 * i, 3);
        Tcl_ListObjAppendList(NULL, e, floats(dl->lines.b + 3 * i, 3));
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewDoubleObj(dl->lines.width[i]));
        add_rgb(e, dl->lines.color[i]);
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewStringObj(dl->lines.style[i] ? "dashed" : "solid", -1));
        return e;
    case 3:
        e = floats(dl->points.xyz + 3 * i, 3);
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewDoubleObj(dl->points.size[i]));
        add_rgb(e, dl->points.color[i]);
        return e;
    case 4: {
        float n[3];
        for (int k = 0; k < 3; k++) n[k] = ms_normal_dequantize(dl->mesh.normal[3 * i + k]);
        e = floats(dl->mesh.xyz + 3 * i, 3);
        Tcl_ListObjAppendList(NULL, e, floats(n, 3));
        add_rgb(e, dl->mesh.color[i]);
        return e;
    }
    default:
        e = Tcl_NewListObj(0, NULL);
        for (int k = 0; k < 3; k++)
            Tcl_ListObjAppendElement(NULL, e, Tcl_NewWideIntObj(dl->mesh.tri[3 * i + k]));
        return e;
    }
}

static int m_repinfo(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const kinds[] = {"spheres", "cylinders", "lines", "points", "vertices",
                                        "triangles", NULL};
    ms_molecule *m;
    ms_rep *r = target(app, interp, objv, 0, "mol repinfo", &m, NULL);
    ms_error err = {{0}};
    if (!r) return TCL_ERROR;
    if (ms_rep_update(app->world.reps, m, r, &err)) return ms_cmd_error(interp, "mol repinfo: %s", err.msg);
    if (objc == 4) {
        Tcl_SetObjResult(interp, counts(app, r));
        return TCL_OK;
    }
    int kind;
    if (ms_arg_choice(interp, objv[4], kinds, "kind", &kind)) return TCL_ERROR;
    const ms_displaylist *dl = ms_rep_list(r);
    size_t n = kind == 0 ? dl->spheres.n : kind == 1 ? dl->cylinders.n : kind == 2 ? dl->lines.n
               : kind == 3 ? dl->points.n : kind == 4 ? dl->mesh.nverts : dl->mesh.ntris;
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    if (kind == 1) n = 0;               /* cylinders: as VMD's pieces, a bond as two halves */
    for (size_t i = 0; i < n; i++) Tcl_ListObjAppendElement(NULL, l, primitive(dl, kind, i));
    ms_dl_pieces it = ms_dl_pieces_of(&dl->cylinders);
    ms_dl_piece p;
    while (kind == 1 && ms_dl_pieces_next(&it, &p)) Tcl_ListObjAppendElement(NULL, l, piece(&p));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

/* ---------------------------------------------------------------- molinfo keywords */

/* "rep i", "selection i", "color i", "material i" */
static int info_get(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *keyword,
                    long frame, Tcl_Obj **out)
{
    ms_rep_what what = MS_REP_STYLE;
    const char *sp = strchr(keyword, ' ');
    char word[32];
    snprintf(word, sizeof word, "%.*s", sp ? (int)(sp - keyword) : 0, keyword);
    what_of(word, &what);
    char *end = NULL;
    long i = sp ? strtol(sp + 1, &end, 10) : -1;
    int ok = sp && end != sp + 1;
    while (ok && isspace((unsigned char)*end)) end++;   /* "{selection 0 }" as VMD reads it */
    ms_rep *r = ok && !*end ? ms_rep_get(app->world.reps, m, i) : NULL;
    if (!r)
        return ms_cmd_error(interp, "%s: %s: molecule %d has no rep '%s' (it has %zu)",
                            ms_args_where(), keyword, m->id, sp ? sp + 1 : "",
                            ms_rep_count(app->world.reps, m));
    *out = Tcl_NewStringObj(ms_rep_text(app->world.reps, r, what), -1);
    return TCL_OK;
}

static int info_numreps(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *keyword,
                        long frame, Tcl_Obj **out)
{
    *out = Tcl_NewWideIntObj((Tcl_WideInt)ms_rep_count(app->world.reps, m));
    return TCL_OK;
}

/* ---------------------------------------------------------------- registration */

static const ms_subcmd rep_table[] = {
    {"representation", m_current, 0, MS_ARGS_ANY, "?<style> ?<parameter> ...??"},
    {"rep", m_current, 0, MS_ARGS_ANY, "?<style> ?<parameter> ...??"},
    {"selection", m_current, 0, MS_ARGS_ANY, "?<selection text>?"},
    {"color", m_current, 0, MS_ARGS_ANY, "?<method> ?<parameter> ...??"},
    {"material", m_current, 0, MS_ARGS_ANY, "?<material>?"},
    {"default", m_default, 1, 2, "color|style|selection|material ?<value>?"},
    {"addrep", m_addrep, 1, 1, "<molid>"},
    {"delrep", m_delrep, 2, 2, "<repid> <molid>"},
    {"modrep", m_modrep, 2, 2, "<repid> <molid>"},
    {"modstyle", m_modify, 3, MS_ARGS_ANY, "<repid> <molid> <style> ?<parameter> ...?"},
    {"modselect", m_modify, 3, MS_ARGS_ANY, "<repid> <molid> <selection text>"},
    {"modcolor", m_modify, 3, MS_ARGS_ANY, "<repid> <molid> <method> ?<parameter> ...?"},
    {"modmaterial", m_modify, 3, MS_ARGS_ANY, "<repid> <molid> <material>"},
    {"showrep", m_flag, 2, 3, "<molid> <repid> ?on|off?"},
    {"selupdate", m_flag, 2, 3, "<repid> <molid> ?on|off?"},
    {"colupdate", m_flag, 2, 3, "<repid> <molid> ?on|off?"},
    {"drawframes", m_drawframes, 2, MS_ARGS_ANY, "<molid> <repid> ?<frames>|now?"},
    {"smoothrep", m_smoothrep, 2, 3, "<molid> <repid> ?<n>?"},
    {"scaleminmax", m_scaleminmax, 2, 4, "<molid> <repid> ?<min> <max>|auto?"},
    {"repname", m_repname, 2, 2, "<molid> <repid>"},
    {"repindex", m_repindex, 2, 2, "<molid> <name>"},
    {"showperiodic", m_periodic, 2, 3, "<molid> <repid> ?<flags of xyzXYZn>?"},
    {"numperiodic", m_periodic, 2, 3, "<molid> <repid> ?<n>?"},
    {"clipplane", m_clipplane, 1, 5, "center|normal|color|status|num ?<clipid> <repid> <molid> ?<value>??"},
    {"repinfo", m_repinfo, 2, 3,
     "<molid> <repid> ?spheres|cylinders|lines|points|vertices|triangles?"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_rep_register(ms_app *app)
{
    ms_cmdset_extend(app, "mol", rep_table);
    static const ms_molinfo_keyword keys[] = {
        {"rep ", 1, info_get, NULL},      {"selection ", 1, info_get, NULL},
        {"color ", 1, info_get, NULL},    {"material ", 1, info_get, NULL},
        {"numreps", 0, info_numreps, NULL}};
    for (size_t i = 0; i < MS_COUNTOF(keys); i++) ms_molinfo_add_keyword(&keys[i]);
}
