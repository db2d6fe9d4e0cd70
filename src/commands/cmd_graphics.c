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
#include "vecmath/vecf.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The user graphics of `graphics <molid> ...` (the molecule was checked by graphics_cmd). */
static ms_ugraphics *graphics_of(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "graphics");
    ms_ugraphics *g = m ? ms_world_ugraphics(&app->world, m) : NULL;
    if (m && !g) ms_cmd_error(interp, "graphics: out of memory");
    return g;
}

static int add_item(ms_app *app, Tcl_Interp *interp, Tcl_Obj *const objv[], ms_ug_item *it)
{
    ms_ugraphics *g = graphics_of(app, interp, objv);
    if (!g) return TCL_ERROR;
    int id = ms_ugraphics_add(g, it);
    if (id < 0) return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    Tcl_SetObjResult(interp, Tcl_NewIntObj(id));
    return TCL_OK;
}

/* n point/normal arguments into it->data. */
static int get_points(Tcl_Interp *interp, int n, Tcl_Obj *const args[], ms_ug_item *it)
{
    for (int i = 0; i < n; i++)
        if (ms_arg_vec3(interp, args[i], NULL, it->data + 3 * i)) return TCL_ERROR;
    return TCL_OK;
}

/* The options of each shape; sizes and resolutions are clamped, as VMD does. */
#define IOFF(f) offsetof(ms_ug_item, f)
#define RADIUS(name, f) {name, MS_OPT_FLOAT, IOFF(f), 0, 0, MS_OPT_MIN | MS_OPT_CLAMP, NULL}
#define RESOLUTION(max) \
    {"resolution", MS_OPT_INT, IOFF(iv[0]), 0, max, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_CLAMP, NULL}
#define END_OPTIONS {NULL, 0, 0, 0, 0, 0, NULL}
static const char *const line_styles[] = {"solid", "dashed", NULL};   /* MS_LINE_* */
static const ms_opt line_options[] = {
    {"width", MS_OPT_INT, IOFF(iv[1]), 0, 255, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_CLAMP, NULL},
    {"style", MS_OPT_ENUM, IOFF(iv[0]), 0, 0, 0, line_styles}, END_OPTIONS};
static const ms_opt cylinder_options[] = {
    RADIUS("radius", radius), RESOLUTION(30), {"filled", MS_OPT_BOOL, IOFF(iv[1]), 0, 0, 0, NULL},
    END_OPTIONS};
static const ms_opt cone_options[] = {RADIUS("radius", radius), RADIUS("radius2", radius2),
                                      RESOLUTION(300), END_OPTIONS};
static const ms_opt sphere_options[] = {RADIUS("radius", radius), RESOLUTION(30), END_OPTIONS};
static const ms_opt text_options[] = {RADIUS("size", size), RADIUS("thickness", thickness),
                                      END_OPTIONS};
static const ms_opt no_options[] = {END_OPTIONS};

/* A shape: its kind, how many points come first, and its options after them. */
static const struct shape {
    const char *name;
    ms_ug_kind kind;
    int npts;
    const ms_opt *options;
} shapes[] = {
    {"point", MS_UG_POINT, 1, no_options},          {"line", MS_UG_LINE, 2, line_options},
    {"cylinder", MS_UG_CYLINDER, 2, cylinder_options}, {"cone", MS_UG_CONE, 2, cone_options},
    {"sphere", MS_UG_SPHERE, 1, sphere_options},    {"triangle", MS_UG_TRIANGLE, 3, no_options},
    {"trinorm", MS_UG_TRINORM, 6, no_options},      {"tricolor", MS_UG_TRICOLOR, 6, no_options},
    {NULL, MS_UG_NONE, 0, NULL}};

/* A colour as graphics takes one: a name, or any integer id, clamped to the ids there are
 * (0..1056) as VMD clamps it; -1 for anything else. */
static int graphics_color(ms_app *app, const char *w)
{
    char *end;
    long v = strtol(w, &end, 10);
    if (*w && *end == '\0') return v < 0 ? 0 : v >= MS_COLOR_MAX ? MS_COLOR_MAX - 1 : (int)v;
    return ms_color_index(app->world.colors, w);
}

static int add_shape(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const struct shape *sh = &shapes[ms_args_find(shapes, sizeof *shapes, Tcl_GetString(objv[2]))];
    int np = sh->npts;
    ms_ug_item it;
    memset(&it, 0, sizeof it);
    it.kind = sh->kind;
    it.radius = 1.0f;
    it.iv[0] = it.kind == MS_UG_LINE ? MS_LINE_SOLID : 6;
    it.iv[1] = it.kind == MS_UG_LINE ? 1 : 0;
    if (get_points(interp, np, objv + 3, &it)) return TCL_ERROR;
    if (it.kind == MS_UG_TRICOLOR) {
        for (int k = 0; k < 3; k++) {
            it.iv[k] = graphics_color(app, Tcl_GetString(objv[9 + k]));
            if (it.iv[k] < 0)
                return ms_cmd_error(interp, "%s: unknown color '%s'", ms_args_where(),
                                    Tcl_GetString(objv[9 + k]));
        }
    } else if (ms_args_options(interp, objc, objv, 3 + np, sh->options, &it, NULL)) {
        return TCL_ERROR;
    }
    if (np == 6) for (int k = 3; k < 6; k++) ms_v3f_normalize(it.data + 3 * k);
    return add_item(app, interp, objv, &it);
}

static int add_text(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_ug_item it;
    memset(&it, 0, sizeof it);
    it.kind = MS_UG_TEXT;
    it.size = it.thickness = 1.0f;
    it.text = Tcl_GetString(objv[4]);
    if (get_points(interp, 1, objv + 3, &it) ||
        ms_args_options(interp, objc, objv, 5, text_options, &it, NULL))
        return TCL_ERROR;
    return add_item(app, interp, objv, &it);
}

/* color, material, materials: items that change the state of those after them */
static int add_state(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_ug_item it;
    memset(&it, 0, sizeof it);
    const char *w = Tcl_GetString(objv[2]), *v = Tcl_GetString(objv[3]);
    if (ms_word_eq(w, "color") || ms_word_eq(w, "colour")) {
        it.kind = MS_UG_COLOR;
        if ((it.iv[0] = graphics_color(app, v)) < 0)
            return ms_cmd_error(interp, "%s: unknown color '%s'", ms_args_where(), v);
    } else if (ms_word_eq(w, "material")) {
        it.kind = MS_UG_MATERIAL;
        int i = ms_material_index(app->world.materials, v);
        if (i < 0) return ms_cmd_error(interp, "%s: unknown material '%s'", ms_args_where(), v);
        it.iv[0] = app->world.materials->list[i].id;
    } else {
        it.kind = MS_UG_MATERIALS;
        if (ms_arg_bool(interp, objv[3], NULL, &it.iv[0])) return TCL_ERROR;
    }
    return add_item(app, interp, objv, &it);
}

static int g_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_ugraphics *g = graphics_of(app, interp, objv);
    if (!g) return TCL_ERROR;
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < g->n; i++)
        if (g->items[i].kind != MS_UG_NONE)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewIntObj(g->items[i].id));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

/* delete / replace / exists / info <id> */
static int manage(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_ugraphics *g = graphics_of(app, interp, objv);
    const char *w = Tcl_GetString(objv[2]);
    if (!g) return TCL_ERROR;
    if (ms_word_eq(w, "delete") && ms_word_eq(Tcl_GetString(objv[3]), "all")) {
        ms_ugraphics_delete_all(g);
        return TCL_OK;
    }
    int id;
    if (Tcl_GetIntFromObj(NULL, objv[3], &id) != TCL_OK)
        return ms_cmd_error(interp, "%s: expected a graphics id, got '%s'", ms_args_where(),
                            Tcl_GetString(objv[3]));
    long i = ms_ugraphics_find(g, id);
    if (ms_word_eq(w, "exists")) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(i >= 0));
        return TCL_OK;
    }
    if (ms_word_eq(w, "delete")) {
        ms_ugraphics_delete(g, id);   /* as VMD: deleting a missing id does nothing */
        return TCL_OK;
    }
    if (i < 0) return ms_cmd_error(interp, "%s: no graphics item with id %d", ms_args_where(), id);
    if (ms_word_eq(w, "replace")) {
        ms_ugraphics_replace(g, id);
        return TCL_OK;
    }
    char buf[2048];
    ms_ugraphics_info(g, i, app->world.materials, buf, sizeof buf);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(buf, -1));
    return TCL_OK;
}

static const ms_subcmd graphics_table[] = {
    {"point", add_shape, 1, 1, "{x y z}"},
    {"line", add_shape, 2, MS_ARGS_ANY, "{x y z} {x y z} ?width <w>? ?style solid|dashed?"},
    {"cylinder", add_shape, 2, MS_ARGS_ANY,
     "{x y z} {x y z} ?radius <r>? ?resolution <n>? ?filled yes|no?"},
    {"cone", add_shape, 2, MS_ARGS_ANY,
     "{x y z} {x y z} ?radius <r>? ?radius2 <r>? ?resolution <n>?"},
    {"sphere", add_shape, 1, MS_ARGS_ANY, "{x y z} ?radius <r>? ?resolution <n>?"},
    {"triangle", add_shape, 3, 3, "{x y z} {x y z} {x y z}"},
    {"trinorm", add_shape, 6, 6, "{x y z} {x y z} {x y z} {nx ny nz} {nx ny nz} {nx ny nz}"},
    {"tricolor", add_shape, 9, 9,
     "{x y z} {x y z} {x y z} {nx ny nz} {nx ny nz} {nx ny nz} <color> <color> <color>"},
    {"text", add_text, 2, MS_ARGS_ANY, "{x y z} <text> ?size <s>? ?thickness <t>?"},
    {"color", add_state, 1, 1, "<color>"},
    {"colour", add_state, 1, 1, "<color>"},
    {"material", add_state, 1, 1, "<material>"},
    {"materials", add_state, 1, 1, "on|off"},
    {"list", g_list, 0, 0, ""},
    {"delete", manage, 1, 1, "<id>|all"},
    {"replace", manage, 1, 1, "<id>"},
    {"exists", manage, 1, 1, "<id>"},
    {"info", manage, 1, 1, "<id>"},
    {NULL, NULL, 0, 0, NULL}};

/* graphics <molid|top> <command> ...: the molecule, then its graphics command */
static int graphics_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    app->world.scene_version++;
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "graphics");
    if (!m) return TCL_ERROR;
    if (!ms_world_ugraphics(&app->world, m)) return ms_cmd_error(interp, "graphics: out of memory");
    char where[48];
    snprintf(where, sizeof where, "graphics %d", m->id);
    return ms_args_dispatch(app, interp, objc, objv, 2, graphics_table, NULL, where);
}

/* draw <shape> args: graphics on the top molecule, or a user's vmd_draw_<shape> proc. */
static int draw_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    app->world.scene_version++;
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
    static const ms_subcmd cmds[] = {
        {"graphics", graphics_cmd, 2, MS_ARGS_ANY, "<molid|top> <command> ?<argument> ...?"},
        {"draw", draw_cmd, 1, MS_ARGS_ANY, "<shape> ?<argument> ...?"}};
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
