/* cmd_scene.c: creating the scene-side state on the application (colours, materials, the
 * view, renderer settings, user graphics), keeping the colour categories in step with the
 * molecules, and registering the scene commands. Also the argument parsers they share. */
#include "config.h"
#include "commands/scenecmds.h"
#include "assemble/devices.h"
#include "scene/color.h"
#include "scene/material.h"
#include "scene/scene.h"
#include "view/view.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int ms_cmd_get_vec3(Tcl_Interp *interp, Tcl_Obj *obj, float v[3], const char *what)
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
    return ms_cmd_error(interp, "%s: expected {x y z}, got '%s'", what, Tcl_GetString(obj));
}

int ms_cmd_get_float(Tcl_Interp *interp, Tcl_Obj *obj, float *out, const char *what)
{
    double d;
    if (Tcl_GetDoubleFromObj(NULL, obj, &d) != TCL_OK || !isfinite(d))
        return ms_cmd_error(interp, "%s: expected a number, got '%s'", what, Tcl_GetString(obj));
    *out = (float)d;
    return TCL_OK;
}

int ms_cmd_get_bool(Tcl_Interp *interp, Tcl_Obj *obj, int *out, const char *what)
{
    if (Tcl_GetBooleanFromObj(NULL, obj, out) != TCL_OK)
        return ms_cmd_error(interp, "%s: expected on or off, got '%s'", what, Tcl_GetString(obj));
    return TCL_OK;
}

Tcl_Obj *ms_cmd_float_obj(double v)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%f", v);
    return Tcl_NewStringObj(buf, -1);
}

ms_ugraphics *ms_cmd_ugraphics(ms_app *app, ms_molecule *m)
{
    if (app->ugraphics_slot < 0) return NULL;
    if (!m->ext[app->ugraphics_slot]) m->ext[app->ugraphics_slot] = ms_ugraphics_new();
    return m->ext[app->ugraphics_slot];
}

/* ---------------------------------------------------------------- state */

static void free_ugraphics(void *p)
{
    ms_ugraphics_free(p);
}

/* User graphics as a source of the scene's display lists. */
static int ugraphics_source(ms_app *app, ms_molecule *m, ms_scene *s, const float model[16],
                            ms_error *err)
{
    if (app->ugraphics_slot < 0 || !m->ext[app->ugraphics_slot]) return 0;
    ms_ugraphics *g = m->ext[app->ugraphics_slot];
    if (ms_ugraphics_update(g, app->colors, err)) return -1;
    for (size_t i = 0; i < g->nlists; i++) {
        if (ms_dl_count(&g->lists[i]) == 0) continue;
        if (ms_scene_add(s, &g->lists[i], model, app->materials, err)) return -1;
    }
    return 0;
}

/* New molecules bring their names, residue names ... into the colour categories. */
static void on_mol_event(void *ud, ms_mol_event ev, ms_molecule *m, const char *arg)
{
    ms_app *app = ud;
    if (ev != MS_EV_MOL_NEW && ev != MS_EV_STRUCTURE) return;
    ms_error err = {{0}};
    if (ms_colors_add_molecule(app->colors, m, &err))
        fprintf(stderr, "molscope: molecule %d: %s\n", m->id, err.msg);
}

static void free_state(ClientData cd, Tcl_Interp *interp)
{
    ms_app *app = cd;
    ms_colors_free(app->colors);
    ms_materials_free(app->materials);
    ms_view_free(app->view);
    ms_renderers_free(app->renderers);
    app->colors = NULL;
    app->materials = NULL;
    app->view = NULL;
    app->renderers = NULL;
}

void ms_cmd_scene_register(ms_app *app)
{
    ms_error err = {{0}};
    app->colors = ms_colors_new(&err);
    app->materials = ms_materials_new(&err);
    app->view = ms_view_new();
    app->renderers = ms_renderers_new();
    if (!app->colors || !app->materials || !app->view || !app->renderers) {
        fprintf(stderr, "molscope: cannot create the scene state (out of memory)\n");
        free_state(app, app->interp);
        return;
    }
    app->ugraphics_slot = ms_molset_register_ext(&app->mols, free_ugraphics);
    ms_molset_listen(&app->mols, on_mol_event, app);
    ms_scene_register_source(ugraphics_source);
    ms_cmd_reset_view = ms_view_reset;
    Tcl_CallWhenDeleted(app->interp, free_state, app);
    ms_cmd_color_register(app);
    ms_cmd_material_register(app);
    ms_cmd_display_register(app);
    ms_cmd_live_register(app);
    ms_cmd_trans_register(app);
    ms_cmd_graphics_register(app);
    ms_cmd_render_register(app);
}
