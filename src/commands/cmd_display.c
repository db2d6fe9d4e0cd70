/* cmd_display.c: the `display`, `axes`, `stage` and `light` commands.
 *
 *   display <setting> <value>        height distance eyesep focallength projection|proj
 *                                    depthcue cuemode cuestart cueend cuedensity shadows
 *                                    ambientocclusion aoambient aodirect dof dof_fnumber
 *                                    dof_focaldist backgroundgradient antialias culling
 *                                    stereo stereoswap rendermode cachemode fps
 *   display nearclip|farclip set|add <v>;  display resize <w> <h>;  display reposition <x> <y>
 *   display get <setting> | size | nearclip | farclip | projections | ...
 *   display resetview;  display update ?on|off|status|ui?
 *   axes location ?<loc>? | locations;  stage location ?<loc>? | locations | panels ?n? | size ?s?
 *   light num | <n> on|off|highlight|unhighlight|status | <n> rot <axis> <deg>
 *         | <n> pos ?{x y z}|default?
 * Invalid values are refused with an error and change nothing. */
#include "config.h"
#include "commands/scenecmds.h"
#include "assemble/view.h"
#include "scene/mat4.h"

#include <stddef.h>
#include <string.h>
#include <strings.h>

typedef enum { S_FLOAT, S_BOOL } stype;

/* A numeric or on/off setting of the view, with its validity rule. */
typedef struct setting {
    const char *name;
    stype type;
    size_t off;
    const char *(*check)(const ms_view *v, float x);
} setting;

static const char *positive(const ms_view *v, float x) { return x > 0 ? NULL : "must be positive"; }
static const char *nonneg(const ms_view *v, float x) { return x >= 0 ? NULL : "must not be negative"; }
static const char *not_eye(const ms_view *v, float x)
{
    return x != v->settings.cam.eye[2] ? NULL : "puts the screen at the eye";
}
static const char *cue_start(const ms_view *v, float x)
{
    return x < 0 ? "must not be negative" : x >= v->settings.cue_end ? "must be less than cueend" : NULL;
}
static const char *cue_end(const ms_view *v, float x)
{
    return x > v->settings.cue_start ? NULL : "must be greater than cuestart";
}

#define VOFF(f) offsetof(ms_view, f)
static const setting settings[] = {
    {"height", S_FLOAT, VOFF(settings.cam.height), positive},
    {"distance", S_FLOAT, VOFF(settings.cam.distance), not_eye},
    {"eyesep", S_FLOAT, VOFF(settings.cam.eyesep), nonneg},
    {"focallength", S_FLOAT, VOFF(settings.cam.focal_length), positive},
    {"cuestart", S_FLOAT, VOFF(settings.cue_start), cue_start},
    {"cueend", S_FLOAT, VOFF(settings.cue_end), cue_end},
    {"cuedensity", S_FLOAT, VOFF(settings.cue_density), nonneg},
    {"aoambient", S_FLOAT, VOFF(settings.ao_ambient), nonneg},
    {"aodirect", S_FLOAT, VOFF(settings.ao_direct), nonneg},
    {"dof_fnumber", S_FLOAT, VOFF(settings.cam.dof_fnumber), positive},
    {"dof_focaldist", S_FLOAT, VOFF(settings.cam.dof_focaldist), positive},
    {"depthcue", S_BOOL, VOFF(settings.depthcue), NULL},
    {"shadows", S_BOOL, VOFF(settings.shadows), NULL},
    {"ambientocclusion", S_BOOL, VOFF(settings.ao), NULL},
    {"dof", S_BOOL, VOFF(settings.cam.dof), NULL},
    {"backgroundgradient", S_BOOL, VOFF(settings.bg_gradient), NULL},
    {"antialias", S_BOOL, VOFF(antialias), NULL},
    {"culling", S_BOOL, VOFF(culling), NULL},
    {"stereoswap", S_BOOL, VOFF(stereoswap), NULL},
    {"fps", S_BOOL, VOFF(fps), NULL}};

/* Words with a fixed set of values: (name, field, values). Only VMD's text-mode choices. */
static const char *const stereo_modes[] = {"Off", NULL};
static const char *const render_modes[] = {"Normal", NULL};
static const char *const cache_modes[] = {"Off", NULL};

static const setting *find_setting(const char *name)
{
    for (size_t i = 0; i < MS_COUNTOF(settings); i++)
        if (ms_word_eq(name, settings[i].name)) return &settings[i];
    return NULL;
}

static int set_value(ms_app *app, Tcl_Interp *interp, const setting *s, Tcl_Obj *val)
{
    char what[64];
    snprintf(what, sizeof what, "display %s", s->name);
    char *p = (char *)app->world.view + s->off;
    if (s->type == S_BOOL) {
        int b;
        if (ms_cmd_get_bool(interp, val, &b, what)) return TCL_ERROR;
        *(int *)p = b;
        return TCL_OK;
    }
    float x;
    if (ms_cmd_get_float(interp, val, &x, what)) return TCL_ERROR;
    const char *bad = s->check ? s->check(app->world.view, x) : NULL;
    if (bad) return ms_cmd_error(interp, "%s: %g %s", what, x, bad);
    *(float *)p = x;
    return TCL_OK;
}

static Tcl_Obj *list_of(const char *const *names, int n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < n && names[i]; i++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(names[i], -1));
    return l;
}

static Tcl_Obj *vec_obj(const float v[3])
{
    Tcl_Obj *e[3];
    for (int k = 0; k < 3; k++) e[k] = ms_cmd_float_obj(v[k]);
    return Tcl_NewListObj(3, e);
}

/* ---------------------------------------------------------------- display get */

static Tcl_Obj *get_word(ms_app *app, const char *w)
{
    const ms_view *v = app->world.view;
    static const char *const projs[] = {"Perspective", "Orthographic"};
    static const char *const cues[] = {"Linear", "Exp", "Exp2"};
    if (ms_word_eq(w, "projection")) return Tcl_NewStringObj(ms_projection_name(v->settings.cam.projection), -1);
    if (ms_word_eq(w, "projections")) return list_of(projs, 2);
    if (ms_word_eq(w, "cuemode")) return Tcl_NewStringObj(ms_cuemode_name(v->settings.cuemode), -1);
    if (ms_word_eq(w, "cuemodes")) return list_of(cues, 3);
    if (ms_word_eq(w, "nearclip")) return ms_cmd_float_obj(v->settings.cam.near_clip);
    if (ms_word_eq(w, "farclip")) return ms_cmd_float_obj(v->settings.cam.far_clip);
    if (ms_word_eq(w, "stereo")) return Tcl_NewStringObj(v->stereo, -1);
    if (ms_word_eq(w, "stereomodes")) return list_of(stereo_modes, 8);
    if (ms_word_eq(w, "rendermode")) return Tcl_NewStringObj(v->rendermode, -1);
    if (ms_word_eq(w, "rendermodes")) return list_of(render_modes, 8);
    if (ms_word_eq(w, "cachemode")) return Tcl_NewStringObj(v->cachemode, -1);
    if (ms_word_eq(w, "cachemodes")) return list_of(cache_modes, 8);
    if (ms_word_eq(w, "eyepos")) return vec_obj(v->settings.cam.eye);
    if (ms_word_eq(w, "eyedir")) return vec_obj(v->settings.cam.dir);
    if (ms_word_eq(w, "eyeup")) return vec_obj(v->settings.cam.up);
    if (ms_word_eq(w, "size")) {
        Tcl_Obj *e[2] = {Tcl_NewIntObj(app->world.width), Tcl_NewIntObj(app->world.height)};
        return Tcl_NewListObj(2, e);
    }
    const setting *s = find_setting(w);
    if (!s) return NULL;
    const char *p = (const char *)app->world.view + s->off;
    if (s->type == S_BOOL) return Tcl_NewStringObj(*(const int *)p ? "on" : "off", -1);
    return ms_cmd_float_obj(*(const float *)p);
}

static int disp_get(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc != 3) return ms_cmd_error(interp, "display get: usage: display get <setting>");
    Tcl_Obj *r = get_word(app, Tcl_GetString(objv[2]));
    if (!r) return ms_cmd_error(interp, "display get: unknown setting '%s'", Tcl_GetString(objv[2]));
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

/* ---------------------------------------------------------------- display setters */

static int disp_setting(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    const setting *s = find_setting(w);
    if (objc == 2) {
        /* `display height` alone reports the value */
        Tcl_SetObjResult(interp, get_word(app, s->name));
        return TCL_OK;
    }
    if (objc != 3) return ms_cmd_error(interp, "display %s: usage: display %s <value>", s->name, s->name);
    return set_value(app, interp, s, objv[2]);
}

/* projection, cuemode, stereo, rendermode, cachemode: a word from a list */
static int disp_choice(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    ms_view *v = app->world.view;
    if (objc == 2) {
        Tcl_SetObjResult(interp, get_word(app, ms_word_eq(w, "proj") ? "projection" : w));
        return TCL_OK;
    }
    if (objc != 3) return ms_cmd_error(interp, "display %s: usage: display %s <value>", w, w);
    const char *val = Tcl_GetString(objv[2]);
    int i;
    if (ms_word_eq(w, "projection") || ms_word_eq(w, "proj")) {
        if ((i = ms_projection_from_name(val)) < 0)
            return ms_cmd_error(interp, "display projection: unknown projection '%s': must be "
                                        "Perspective or Orthographic", val);
        v->settings.cam.projection = (ms_projection)i;
    } else if (ms_word_eq(w, "cuemode")) {
        if ((i = ms_cuemode_from_name(val)) < 0)
            return ms_cmd_error(interp, "display cuemode: unknown cue mode '%s': must be Linear, "
                                        "Exp or Exp2", val);
        v->settings.cuemode = (ms_cuemode)i;
    } else {
        const char *const *modes = ms_word_eq(w, "stereo") ? stereo_modes
                                   : ms_word_eq(w, "rendermode") ? render_modes : cache_modes;
        char *field = ms_word_eq(w, "stereo") ? v->stereo
                      : ms_word_eq(w, "rendermode") ? v->rendermode : v->cachemode;
        for (i = 0; modes[i] && strcasecmp(modes[i], val); i++) continue;
        if (!modes[i])
            return ms_cmd_error(interp, "display %s: mode '%s' is not available (this display "
                                        "has: %s)", w, val, modes[0]);
        snprintf(field, 16, "%s", modes[i]);
    }
    return TCL_OK;
}

static int disp_clip(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    int near = ms_word_eq(w, "nearclip");
    ms_camera *c = &app->world.view->settings.cam;
    if (objc == 2) {
        Tcl_SetObjResult(interp, ms_cmd_float_obj(near ? c->near_clip : c->far_clip));
        return TCL_OK;
    }
    const char *how = objc == 4 ? Tcl_GetString(objv[2]) : "";
    if (objc != 4 || (!ms_word_eq(how, "set") && !ms_word_eq(how, "add")))
        return ms_cmd_error(interp, "display %s: usage: display %s set|add <value>", w, w);
    float x;
    if (ms_cmd_get_float(interp, objv[3], &x, near ? "display nearclip" : "display farclip"))
        return TCL_ERROR;
    if (ms_word_eq(how, "add")) x += near ? c->near_clip : c->far_clip;
    if (near && (x <= 0 || x >= c->far_clip))
        return ms_cmd_error(interp, "display nearclip: %g must be positive and less than the far "
                                    "clip %g", x, c->far_clip);
    if (!near && x <= c->near_clip)
        return ms_cmd_error(interp, "display farclip: %g must be greater than the near clip %g",
                            x, c->near_clip);
    if (near) c->near_clip = x;
    else c->far_clip = x;
    return TCL_OK;
}

static int disp_resize(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int wh[2];
    if (objc != 4) return ms_cmd_error(interp, "display resize: usage: display resize <width> <height>");
    for (int k = 0; k < 2; k++)
        if (Tcl_GetIntFromObj(NULL, objv[2 + k], &wh[k]) != TCL_OK || wh[k] < 1 || wh[k] > 32768)
            return ms_cmd_error(interp, "display resize: %s: expected a whole number from 1 to "
                                        "32768, got '%s'", k ? "height" : "width",
                                Tcl_GetString(objv[2 + k]));
    app->world.width = wh[0];
    app->world.height = wh[1];
    return TCL_OK;
}

static int disp_reposition(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int x, y;
    if (objc != 4 || Tcl_GetIntFromObj(NULL, objv[2], &x) != TCL_OK ||
        Tcl_GetIntFromObj(NULL, objv[3], &y) != TCL_OK)
        return ms_cmd_error(interp, "display reposition: usage: display reposition <x> <y> (whole numbers)");
    return TCL_OK;   /* no window to move */
}

static int disp_size(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc != 2)
        return ms_cmd_error(interp, "display size: the size is read-only here; use display resize <w> <h>");
    Tcl_SetObjResult(interp, get_word(app, "size"));
    return TCL_OK;
}

static int disp_resetview(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc != 2) return ms_cmd_error(interp, "display resetview: takes no arguments");
    ms_view_reset(&app->world);
    return TCL_OK;
}

static int disp_update(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 2) {
        ms_view_rock_step(&app->world);   /* a redraw advances rocking, as VMD's display loop does */
        return TCL_OK;
    }
    const char *w = objc == 3 ? Tcl_GetString(objv[2]) : "";
    int b;
    if (!strcmp(w, "status")) Tcl_SetObjResult(interp, Tcl_NewIntObj(app->world.view->update));
    else if (!strcmp(w, "ui")) return TCL_OK;
    else if (objc == 3 && Tcl_GetBooleanFromObj(NULL, objv[2], &b) == TCL_OK) app->world.view->update = b;
    else return ms_cmd_error(interp, "display update: usage: display update ?on|off|status|ui?");
    return TCL_OK;
}

/* ---------------------------------------------------------------- axes, stage */

static int axes_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = objc > 1 ? Tcl_GetString(objv[1]) : "";
    ms_view *v = app->world.view;
    if (objc == 2 && ms_word_eq(w, "locations")) {
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (int i = 0; i < MS_AXES_NLOCS; i++)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_axes_loc_name((ms_axes_loc)i), -1));
        Tcl_SetObjResult(interp, l);
        return TCL_OK;
    }
    if (!ms_word_eq(w, "location") || objc > 3)
        return ms_cmd_error(interp, "axes: usage: axes location ?Off|Origin|LowerLeft|LowerRight|"
                                    "UpperLeft|UpperRight? | axes locations");
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_axes_loc_name(v->axes), -1));
        return TCL_OK;
    }
    int l = ms_axes_loc_from_name(Tcl_GetString(objv[2]));
    if (l < 0) return ms_cmd_error(interp, "axes location: unknown location '%s'", Tcl_GetString(objv[2]));
    v->axes = (ms_axes_loc)l;
    return TCL_OK;
}

static int stage_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = objc > 1 ? Tcl_GetString(objv[1]) : "";
    ms_view *v = app->world.view;
    if (objc == 2 && ms_word_eq(w, "locations")) {
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (int i = 0; i < MS_STAGE_NLOCS; i++)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_stage_loc_name((ms_stage_loc)i), -1));
        Tcl_SetObjResult(interp, l);
        return TCL_OK;
    }
    if (objc == 2 || objc == 3) {
        if (ms_word_eq(w, "location")) {
            if (objc == 2) {
                Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_stage_loc_name(v->stage), -1));
                return TCL_OK;
            }
            int l = ms_stage_loc_from_name(Tcl_GetString(objv[2]));
            if (l < 0) return ms_cmd_error(interp, "stage location: unknown location '%s'", Tcl_GetString(objv[2]));
            v->stage = (ms_stage_loc)l;
            return TCL_OK;
        }
        if (ms_word_eq(w, "panels")) {
            long n;
            if (objc == 2) {
                Tcl_SetObjResult(interp, Tcl_NewIntObj(v->stage_panels));
                return TCL_OK;
            }
            if (ms_cmd_get_count(interp, objv[2], 30, "stage panels", &n)) return TCL_ERROR;
            if (n < 1) return ms_cmd_error(interp, "stage panels: needs at least 1 panel");
            v->stage_panels = (int)n;
            return TCL_OK;
        }
        if (ms_word_eq(w, "size")) {
            float s;
            if (objc == 2) {
                Tcl_SetObjResult(interp, ms_cmd_float_obj(v->stage_size));
                return TCL_OK;
            }
            if (ms_cmd_get_float(interp, objv[2], &s, "stage size")) return TCL_ERROR;
            if (s <= 0) return ms_cmd_error(interp, "stage size: %g must be positive", s);
            v->stage_size = s;
            return TCL_OK;
        }
    }
    return ms_cmd_error(interp, "stage: usage: stage location ?<loc>? | locations | panels ?<n>? | size ?<s>?");
}

/* ---------------------------------------------------------------- light */

static int light_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_view *v = app->world.view;
    if (objc == 2 && ms_word_eq(Tcl_GetString(objv[1]), "num")) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(MS_SCENE_LIGHTS));
        return TCL_OK;
    }
    int n;
    if (objc < 3 || Tcl_GetIntFromObj(NULL, objv[1], &n) != TCL_OK)
        return ms_cmd_error(interp, "light: usage: light num | light <n> on|off|highlight|"
                                    "unhighlight|status | light <n> rot <axis> <deg> | light <n> pos ?{x y z}|default?");
    if (n < 0 || n >= MS_SCENE_LIGHTS)
        return ms_cmd_error(interp, "light: no light %d (lights are 0 to %d)", n, MS_SCENE_LIGHTS - 1);
    ms_light *l = &v->settings.lights[n];
    const char *w = Tcl_GetString(objv[2]);
    if (objc == 3) {
        if (ms_word_eq(w, "on") || ms_word_eq(w, "off")) l->on = ms_word_eq(w, "on");
        else if (ms_word_eq(w, "highlight") || ms_word_eq(w, "unhighlight"))
            v->light_highlight[n] = ms_word_eq(w, "highlight");
        else if (ms_word_eq(w, "status"))
            Tcl_SetObjResult(interp, Tcl_ObjPrintf("%s %s", l->on ? "on" : "off",
                                                   v->light_highlight[n] ? "highlight" : "unhighlight"));
        else if (ms_word_eq(w, "pos"))
            Tcl_SetObjResult(interp, vec_obj(l->pos));
        else
            return ms_cmd_error(interp, "light %d: unknown option '%s'", n, w);
        return TCL_OK;
    }
    if (objc == 4 && ms_word_eq(w, "pos")) {
        if (!strcasecmp(Tcl_GetString(objv[3]), "default")) {
            /* as VMD: reports the default position (the caller sets it if it wants) */
            Tcl_SetObjResult(interp, vec_obj(ms_view_default_light(n)));
            return TCL_OK;
        }
        return ms_cmd_get_vec3(interp, objv[3], l->pos, "light pos");
    }
    if (objc == 5 && ms_word_eq(w, "rot")) {
        const char *ax = Tcl_GetString(objv[3]);
        float deg, r[16];
        if (strlen(ax) != 1 || !strchr("xyzXYZ", ax[0]))
            return ms_cmd_error(interp, "light rot: unknown axis '%s': must be x, y or z", ax);
        if (ms_cmd_get_float(interp, objv[4], &deg, "light rot")) return TCL_ERROR;
        ms_mat4_rotation(r, ax[0], deg);
        ms_mat4_point(r, l->pos, l->pos);
        return TCL_OK;
    }
    return ms_cmd_error(interp, "light %d: usage: light <n> rot <axis> <deg> | light <n> pos ?{x y z}|default?", n);
}

/* ---------------------------------------------------------------- registration */

static int axes_proc(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ((ms_app *)cd)->world.scene_version++;
    return axes_cmd(cd, interp, objc, objv);
}

static int stage_proc(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ((ms_app *)cd)->world.scene_version++;
    return stage_cmd(cd, interp, objc, objv);
}

static int light_proc(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ((ms_app *)cd)->world.scene_version++;
    return light_cmd(cd, interp, objc, objv);
}

static const ms_subcmd display_table[] = {
    {"resetview", disp_resetview}, {"update", disp_update},
    {"resize", disp_resize}, {"reposition", disp_reposition}, {"size", disp_size},
    {"nearclip", disp_clip}, {"farclip", disp_clip},
    {"projection", disp_choice}, {"proj", disp_choice}, {"cuemode", disp_choice},
    {"stereo", disp_choice}, {"rendermode", disp_choice}, {"cachemode", disp_choice},
    {NULL, NULL}};

void ms_cmd_display_register(ms_app *app)
{
    static const ms_subcmd queries[] = {{"get", disp_get}, {NULL, NULL}};
    ms_cmdset_create(app, "display", display_table);
    ms_cmdset_extend_quiet(app, "display", queries);
    ms_subcmd one[2] = {{NULL, disp_setting}, {NULL, NULL}};
    for (size_t i = 0; i < MS_COUNTOF(settings); i++) {
        one[0].name = settings[i].name;
        ms_cmdset_extend(app, "display", one);
    }
    Tcl_CreateObjCommand(app->interp, "axes", axes_proc, app, NULL);
    Tcl_CreateObjCommand(app->interp, "stage", stage_proc, app, NULL);
    Tcl_CreateObjCommand(app->interp, "light", light_proc, app, NULL);
}
