/* cmd_graphics.c: the `graphics` and `draw` commands (VMD's user graphics).
 *
 *   graphics <molid|top> point {x y z}
 *   graphics <molid|top> line {a} {b} ?width 1..255? ?style solid|dashed?
 *   graphics <molid|top> cylinder {a} {b} ?radius r? ?resolution 0..30? ?filled yes|no?
 *   graphics <molid|top> cone {base} {tip} ?radius r? ?radius2 r? ?resolution 0..300?
 *   graphics <molid|top> sphere {c} ?radius r? ?resolution 0..30?
 *   graphics <molid|top> triangle {a} {b} {c}  |  trinorm ... {na} {nb} {nc}
 *                      | tricolor ... {na} {nb} {nc} <ca> <cb> <cc>
 *   graphics <molid|top> text {p} "string" ?size s? ?thickness t?
 *   graphics <molid|top> color <color> | material <name> | materials on|off
 *                                                      -> each returns the new item's id
 *   graphics <molid|top> delete <id|all> | replace <id> | exists <id> | info <id> | list
 *   draw <shape> args...   = graphics top ... (an empty "graphics" molecule is made when
 *                            there is none); a proc vmd_draw_<shape> is called instead when
 *                            it exists, with the molecule id first. */
#include "config.h"
#include "commands/scenecmds.h"
#include "scene/material.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct gctx {
    ms_app *app;
    Tcl_Interp *interp;
    ms_ugraphics *g;
    const char *shape;
    char what[64];
} gctx;

static int add_item(gctx *c, ms_ug_item *it)
{
    int id = ms_ugraphics_add(c->g, it);
    if (id < 0) return ms_cmd_error(c->interp, "graphics: %s: out of memory", c->shape);
    Tcl_SetObjResult(c->interp, Tcl_NewIntObj(id));
    return TCL_OK;
}

/* n point/normal arguments into it->data. */
static int get_points(gctx *c, int n, Tcl_Obj *const args[], ms_ug_item *it)
{
    for (int i = 0; i < n; i++)
        if (ms_cmd_get_vec3(c->interp, args[i], it->data + 3 * i, c->what)) return TCL_ERROR;
    return TCL_OK;
}

static int get_int_opt(gctx *c, Tcl_Obj *o, int lo, int hi, int *out, const char *opt)
{
    if (Tcl_GetIntFromObj(NULL, o, out) != TCL_OK)
        return ms_cmd_error(c->interp, "%s: %s: expected an integer, got '%s'", c->what, opt,
                            Tcl_GetString(o));
    *out = *out < lo ? lo : *out > hi ? hi : *out;   /* VMD clamps */
    return TCL_OK;
}

static int get_radius(gctx *c, Tcl_Obj *o, float *out, const char *opt)
{
    char what[96];
    snprintf(what, sizeof what, "%s: %s", c->what, opt);
    if (ms_cmd_get_float(c->interp, o, out, what)) return TCL_ERROR;
    if (*out < 0) *out = 0;                       /* VMD clamps */
    return TCL_OK;
}

/* Option pairs after the points: the shape's allowed names decide what is parsed. */
static int options(gctx *c, int n, Tcl_Obj *const args[], ms_ug_item *it)
{
    if (n % 2)
        return ms_cmd_error(c->interp, "%s: options come in pairs, got an odd number", c->what);
    int cyl = it->kind == MS_UG_CYLINDER, cone = it->kind == MS_UG_CONE;
    int sph = it->kind == MS_UG_SPHERE, line = it->kind == MS_UG_LINE, text = it->kind == MS_UG_TEXT;
    for (int i = 0; i < n; i += 2) {
        const char *o = Tcl_GetString(args[i]);
        Tcl_Obj *v = args[i + 1];
        int b, rc;
        if ((cyl || cone || sph) && !strcasecmp(o, "radius")) rc = get_radius(c, v, &it->radius, o);
        else if (cone && !strcasecmp(o, "radius2")) rc = get_radius(c, v, &it->radius2, o);
        else if ((cyl || sph) && !strcasecmp(o, "resolution")) rc = get_int_opt(c, v, 0, 30, &it->iv[0], o);
        else if (cone && !strcasecmp(o, "resolution")) rc = get_int_opt(c, v, 0, 300, &it->iv[0], o);
        else if (cyl && !strcasecmp(o, "filled")) {
            rc = ms_cmd_get_bool(c->interp, v, &b, c->what);
            it->iv[1] = b;
        } else if (line && !strcasecmp(o, "width")) rc = get_int_opt(c, v, 0, 255, &it->iv[1], o);
        else if (line && !strcasecmp(o, "style")) {
            const char *s = Tcl_GetString(v);
            rc = TCL_OK;
            if (!strcasecmp(s, "solid")) it->iv[0] = MS_LINE_SOLID;
            else if (!strcasecmp(s, "dashed")) it->iv[0] = MS_LINE_DASHED;
            else rc = ms_cmd_error(c->interp, "%s: unknown line style '%s': must be solid or dashed", c->what, s);
        } else if (text && !strcasecmp(o, "size")) rc = get_radius(c, v, &it->size, o);
        else if (text && !strcasecmp(o, "thickness")) rc = get_radius(c, v, &it->thickness, o);
        else rc = ms_cmd_error(c->interp, "%s: unknown option '%s'", c->what, o);
        if (rc) return TCL_ERROR;
    }
    return TCL_OK;
}

static void normalize(float *n)
{
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) for (int k = 0; k < 3; k++) n[k] /= l;
}

/* A shape: its kind, how many points it takes first, and whether the rest is fixed. */
static int add_shape(gctx *c, int objc, Tcl_Obj *const objv[])
{
    static const struct {
        const char *name;
        ms_ug_kind kind;
        int npts, exact;
    } shapes[] = {
        {"point", MS_UG_POINT, 1, 1}, {"line", MS_UG_LINE, 2, 0}, {"cylinder", MS_UG_CYLINDER, 2, 0},
        {"cone", MS_UG_CONE, 2, 0}, {"sphere", MS_UG_SPHERE, 1, 0}, {"triangle", MS_UG_TRIANGLE, 3, 1},
        {"trinorm", MS_UG_TRINORM, 6, 1}, {"tricolor", MS_UG_TRICOLOR, 6, 0}};
    for (size_t s = 0; s < MS_COUNTOF(shapes); s++) {
        if (strcasecmp(c->shape, shapes[s].name)) continue;
        int nargs = objc - 3, np = shapes[s].npts;
        int need = shapes[s].kind == MS_UG_TRICOLOR ? 9 : np;
        if (nargs < need || (shapes[s].exact && nargs != need) ||
            (shapes[s].kind == MS_UG_TRICOLOR && nargs != 9))
            return ms_cmd_error(c->interp, "%s: expected %s%d arguments, got %d", c->what,
                                shapes[s].exact || need == 9 ? "" : "at least ", need, nargs);
        ms_ug_item it;
        memset(&it, 0, sizeof it);
        it.kind = shapes[s].kind;
        it.radius = 1.0f;
        it.iv[0] = it.kind == MS_UG_LINE ? MS_LINE_SOLID : 6;
        it.iv[1] = it.kind == MS_UG_LINE ? 1 : 0;
        if (get_points(c, np, objv + 3, &it)) return TCL_ERROR;
        if (it.kind == MS_UG_TRICOLOR) {
            for (int k = 0; k < 3; k++) {
                it.iv[k] = ms_color_index(c->app->world.colors, Tcl_GetString(objv[9 + k]));
                if (it.iv[k] < 0)
                    return ms_cmd_error(c->interp, "%s: unknown color '%s'", c->what, Tcl_GetString(objv[9 + k]));
            }
        } else if (options(c, nargs - np, objv + 3 + np, &it)) {
            return TCL_ERROR;
        }
        if (np == 6) for (int k = 3; k < 6; k++) normalize(it.data + 3 * k);
        return add_item(c, &it);
    }
    return ms_cmd_error(c->interp, "graphics: unknown graphics command '%s': must be point, line, "
                                   "cylinder, cone, sphere, triangle, trinorm, tricolor, text, "
                                   "color, material, materials, delete, replace, exists, info or list",
                        c->shape);
}

static int add_text(gctx *c, int objc, Tcl_Obj *const objv[])
{
    if (objc < 5) return ms_cmd_error(c->interp, "%s: usage: text {x y z} <string> ?size s? ?thickness t?", c->what);
    ms_ug_item it;
    memset(&it, 0, sizeof it);
    it.kind = MS_UG_TEXT;
    it.size = it.thickness = 1.0f;
    it.text = Tcl_GetString(objv[4]);
    if (get_points(c, 1, objv + 3, &it) || options(c, objc - 5, objv + 5, &it)) return TCL_ERROR;
    return add_item(c, &it);
}

static int add_state(gctx *c, int objc, Tcl_Obj *const objv[])
{
    if (objc != 4) return ms_cmd_error(c->interp, "%s: takes one argument", c->what);
    ms_ug_item it;
    memset(&it, 0, sizeof it);
    const char *v = Tcl_GetString(objv[3]);
    if (!strcasecmp(c->shape, "color") || !strcasecmp(c->shape, "colour")) {
        it.kind = MS_UG_COLOR;
        if ((it.iv[0] = ms_color_index(c->app->world.colors, v)) < 0)
            return ms_cmd_error(c->interp, "%s: unknown color '%s'", c->what, v);
    } else if (!strcasecmp(c->shape, "material")) {
        it.kind = MS_UG_MATERIAL;
        int i = ms_material_index(c->app->world.materials, v);
        if (i < 0) return ms_cmd_error(c->interp, "%s: unknown material '%s'", c->what, v);
        it.iv[0] = c->app->world.materials->list[i].id;
    } else {
        it.kind = MS_UG_MATERIALS;
        if (ms_cmd_get_bool(c->interp, objv[3], &it.iv[0], c->what)) return TCL_ERROR;
    }
    return add_item(c, &it);
}

/* delete / replace / exists / info / list */
static int manage(gctx *c, int objc, Tcl_Obj *const objv[])
{
    Tcl_Interp *interp = c->interp;
    if (!strcasecmp(c->shape, "list")) {
        if (objc != 3) return ms_cmd_error(interp, "graphics list: takes no arguments");
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (size_t i = 0; i < c->g->n; i++)
            if (c->g->items[i].kind != MS_UG_NONE)
                Tcl_ListObjAppendElement(NULL, l, Tcl_NewIntObj(c->g->items[i].id));
        Tcl_SetObjResult(interp, l);
        return TCL_OK;
    }
    if (objc != 4) return ms_cmd_error(interp, "%s: takes one argument", c->what);
    if (!strcasecmp(c->shape, "delete") && !strcasecmp(Tcl_GetString(objv[3]), "all")) {
        ms_ugraphics_delete_all(c->g);
        return TCL_OK;
    }
    int id;
    if (Tcl_GetIntFromObj(NULL, objv[3], &id) != TCL_OK)
        return ms_cmd_error(interp, "%s: expected a graphics id, got '%s'", c->what, Tcl_GetString(objv[3]));
    long i = ms_ugraphics_find(c->g, id);
    if (!strcasecmp(c->shape, "exists")) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(i >= 0));
        return TCL_OK;
    }
    if (!strcasecmp(c->shape, "delete")) {
        ms_ugraphics_delete(c->g, id);   /* as VMD: deleting a missing id does nothing */
        return TCL_OK;
    }
    if (i < 0) return ms_cmd_error(interp, "%s: no graphics item with id %d", c->what, id);
    if (!strcasecmp(c->shape, "replace")) {
        ms_ugraphics_replace(c->g, id);
        return TCL_OK;
    }
    char buf[2048];
    ms_ugraphics_info(c->g, i, c->app->world.materials, buf, sizeof buf);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(buf, -1));
    return TCL_OK;
}

static int graphics_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_app *app = cd;
    app->world.scene_version++;
    if (objc < 3)
        return ms_cmd_error(interp, "graphics: usage: graphics <molid|top> <command> ?args?");
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "graphics");
    if (!m) return TCL_ERROR;
    gctx c = {app, interp, ms_world_ugraphics(&app->world, m), Tcl_GetString(objv[2]), ""};
    if (!c.g) return ms_cmd_error(interp, "graphics: out of memory");
    snprintf(c.what, sizeof c.what, "graphics %d %s", m->id, c.shape);
    if (!strcasecmp(c.shape, "text")) return add_text(&c, objc, objv);
    if (!strcasecmp(c.shape, "color") || !strcasecmp(c.shape, "colour") ||
        !strcasecmp(c.shape, "material") || !strcasecmp(c.shape, "materials"))
        return add_state(&c, objc, objv);
    static const char *const manage_words[] = {"list", "delete", "replace", "exists", "info"};
    for (size_t i = 0; i < MS_COUNTOF(manage_words); i++)
        if (!strcasecmp(c.shape, manage_words[i])) return manage(&c, objc, objv);
    return add_shape(&c, objc, objv);
}

/* draw <shape> args: graphics on the top molecule, or a user's vmd_draw_<shape> proc. */
static int draw_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_app *app = cd;
    app->world.scene_version++;
    if (objc < 2) return ms_cmd_error(interp, "draw: usage: draw <shape> ?args?");
    ms_molecule *top = ms_molset_top(&app->mols);
    if (!top) {
        ms_error err = {{0}};
        top = ms_mol_new(&err);
        if (!top || !(top->name = ms_strdup("graphics")) || ms_molset_add(&app->mols, top, &err)) {
            ms_mol_free(top);
            return ms_cmd_error(interp, "draw: out of memory");
        }
    }
    Tcl_Obj *proc = Tcl_ObjPrintf("vmd_draw_%s", Tcl_GetString(objv[1]));
    Tcl_IncrRefCount(proc);
    Tcl_CmdInfo info;
    int user = Tcl_GetCommandInfo(interp, Tcl_GetString(proc), &info);
    Tcl_Obj *call = Tcl_NewListObj(0, NULL);
    Tcl_IncrRefCount(call);
    Tcl_ListObjAppendElement(NULL, call, user ? proc : Tcl_NewStringObj("graphics", -1));
    Tcl_ListObjAppendElement(NULL, call, Tcl_NewIntObj(top->id));
    for (int i = user ? 2 : 1; i < objc; i++) Tcl_ListObjAppendElement(NULL, call, objv[i]);
    int rc = Tcl_EvalObjEx(interp, call, 0);
    Tcl_DecrRefCount(call);
    Tcl_DecrRefCount(proc);
    return rc;
}

void ms_cmd_graphics_register(ms_app *app)
{
    Tcl_CreateObjCommand(app->interp, "graphics", graphics_cmd, app, NULL);
    Tcl_CreateObjCommand(app->interp, "draw", draw_cmd, app, NULL);
}
