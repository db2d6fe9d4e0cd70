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
#include "vecmath/vecf.h"

#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

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
    char *p = (char *)app->world.view + s->off;
    if (s->type == S_BOOL) return ms_arg_bool(interp, val, NULL, (int *)p);
    float x;
    if (ms_arg_float(interp, val, NULL, &x)) return TCL_ERROR;
    const char *bad = s->check ? s->check(app->world.view, x) : NULL;
    if (bad) return ms_cmd_error(interp, "%s: %g %s", ms_args_where(), x, bad);
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

/* The words of display get besides the settings. */
typedef enum {
    W_PROJECTION, W_PROJECTIONS, W_CUEMODE, W_CUEMODES, W_NEARCLIP, W_FARCLIP, W_STEREO,
    W_STEREOMODES, W_RENDERMODE, W_RENDERMODES, W_CACHEMODE, W_CACHEMODES, W_EYEPOS, W_EYEDIR,
    W_EYEUP, W_SIZE, W_COUNT
} get_word_id;
static const char *const get_words[W_COUNT + 1] = {
    "projection", "projections", "cuemode", "cuemodes", "nearclip", "farclip", "stereo",
    "stereomodes", "rendermode", "rendermodes", "cachemode", "cachemodes", "eyepos", "eyedir",
    "eyeup", "size", NULL};

static Tcl_Obj *get_word(ms_app *app, const char *w)
{
    const ms_view *v = app->world.view;
    static const char *const projs[] = {"Perspective", "Orthographic"};
    static const char *const cues[] = {"Linear", "Exp", "Exp2"};
    Tcl_Obj *e[2];
    switch ((get_word_id)ms_args_find(get_words, sizeof *get_words, w)) {
    case W_PROJECTION: return Tcl_NewStringObj(ms_projection_name(v->settings.cam.projection), -1);
    case W_PROJECTIONS: return list_of(projs, 2);
    case W_CUEMODE: return Tcl_NewStringObj(ms_cuemode_name(v->settings.cuemode), -1);
    case W_CUEMODES: return list_of(cues, 3);
    case W_NEARCLIP: return ms_cmd_float_obj(v->settings.cam.near_clip);
    case W_FARCLIP: return ms_cmd_float_obj(v->settings.cam.far_clip);
    case W_STEREO: return Tcl_NewStringObj(v->stereo, -1);
    case W_STEREOMODES: return list_of(stereo_modes, 8);
    case W_RENDERMODE: return Tcl_NewStringObj(v->rendermode, -1);
    case W_RENDERMODES: return list_of(render_modes, 8);
    case W_CACHEMODE: return Tcl_NewStringObj(v->cachemode, -1);
    case W_CACHEMODES: return list_of(cache_modes, 8);
    case W_EYEPOS: return vec_obj(v->settings.cam.eye);
    case W_EYEDIR: return vec_obj(v->settings.cam.dir);
    case W_EYEUP: return vec_obj(v->settings.cam.up);
    case W_SIZE:
        e[0] = Tcl_NewIntObj(app->world.width);
        e[1] = Tcl_NewIntObj(app->world.height);
        return Tcl_NewListObj(2, e);
    default:
        break;
    }
    const setting *s = find_setting(w);
    if (!s) return NULL;
    const char *p = (const char *)app->world.view + s->off;
    if (s->type == S_BOOL) return Tcl_NewStringObj(*(const int *)p ? "on" : "off", -1);
    return ms_cmd_float_obj(*(const float *)p);
}

static int disp_get(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *r = get_word(app, Tcl_GetString(objv[2]));
    if (!r) {   /* the words, then the settings */
        size_t n = W_COUNT + MS_COUNTOF(settings);
        Tcl_Obj *msg = Tcl_ObjPrintf("%s: unknown setting \"%s\": must be ", ms_args_where(),
                                     Tcl_GetString(objv[2]));
        for (size_t i = 0; i < n; i++)
            Tcl_AppendPrintfToObj(msg, "%s%s", i == 0 ? "" : i + 1 == n ? ", or " : ", ",
                                  i < W_COUNT ? get_words[i] : settings[i - W_COUNT].name);
        Tcl_SetObjResult(interp, msg);
        return TCL_ERROR;
    }
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

/* ---------------------------------------------------------------- display setters */

static int disp_setting(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const setting *s = find_setting(Tcl_GetString(objv[1]));
    if (objc == 2) {
        /* `display height` alone reports the value */
        Tcl_SetObjResult(interp, get_word(app, s->name));
        return TCL_OK;
    }
    return set_value(app, interp, s, objv[2]);
}

/* A word from names (n of them) into *index; the error lists them. */
static int pick(Tcl_Interp *interp, Tcl_Obj *word, const char *(*name)(int), int n,
                const char *what, int *index)
{
    const char *names[16] = {NULL};
    for (int i = 0; i < n && i < 15; i++) names[i] = name(i);
    return ms_arg_choice(interp, word, names, what, index);
}

static const char *projection_name(int i) { return ms_projection_name((ms_projection)i); }
static const char *cuemode_name(int i) { return ms_cuemode_name((ms_cuemode)i); }
static const char *axes_name(int i) { return ms_axes_loc_name((ms_axes_loc)i); }
static const char *stage_name(int i) { return ms_stage_loc_name((ms_stage_loc)i); }

/* projection, cuemode, stereo, rendermode, cachemode: a word from a list */
static int disp_choice(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    ms_view *v = app->world.view;
    int proj = ms_word_eq(w, "projection") || ms_word_eq(w, "proj");
    if (objc == 2) {
        Tcl_SetObjResult(interp, get_word(app, proj ? "projection" : w));
        return TCL_OK;
    }
    int i;
    if (proj) {
        if (pick(interp, objv[2], projection_name, 2, "projection", &i)) return TCL_ERROR;
        v->settings.cam.projection = (ms_projection)i;
    } else if (ms_word_eq(w, "cuemode")) {
        if (pick(interp, objv[2], cuemode_name, 3, "cue mode", &i)) return TCL_ERROR;
        v->settings.cuemode = (ms_cuemode)i;
    } else {
        int stereo = ms_word_eq(w, "stereo"), render = ms_word_eq(w, "rendermode");
        const char *const *modes = stereo ? stereo_modes : render ? render_modes : cache_modes;
        char *field = stereo ? v->stereo : render ? v->rendermode : v->cachemode;
        const char *val = Tcl_GetString(objv[2]);
        static const char *const vmd_render_modes[] = {"GLSL", "Acrobat3D", "Tachyon RTRT",
                                                       "Tachyon OptiX", "Tachyon OSPRay",
                                                       "Tachyon ANARI", NULL};
        if (render && ms_args_find(vmd_render_modes, sizeof *vmd_render_modes, val) >= 0) {
            /* VMD's OpenGL modes: the pictures come from the renderers here */
            printf("Info) display rendermode: '%s' is not available here; keeping %s\n", val,
                   field);
            fflush(stdout);
            return TCL_OK;
        }
        if ((i = ms_args_find(modes, sizeof *modes, val)) < 0)
            return ms_cmd_error(interp, "%s: mode '%s' is not available (this display has: %s)",
                                ms_args_where(), val, modes[0]);
        snprintf(field, 16, "%s", modes[i]);
    }
    return TCL_OK;
}

static int disp_clip(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const how_words[] = {"set", "add", NULL};
    int near = ms_word_eq(Tcl_GetString(objv[1]), "nearclip"), add;
    ms_camera *c = &app->world.view->settings.cam;
    if (objc == 2) {
        Tcl_SetObjResult(interp, ms_cmd_float_obj(near ? c->near_clip : c->far_clip));
        return TCL_OK;
    }
    if (objc != 4) return ms_args_usage(interp);
    float x;
    if (ms_arg_choice(interp, objv[2], how_words, NULL, &add) ||
        ms_arg_float(interp, objv[3], NULL, &x))
        return TCL_ERROR;
    if (add) x += near ? c->near_clip : c->far_clip;
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
    int w, h;
    if (ms_arg_int(interp, objv[2], "width", 1, 32768, &w) ||
        ms_arg_int(interp, objv[3], "height", 1, 32768, &h))
        return TCL_ERROR;
    app->world.width = w;
    app->world.height = h;
    return TCL_OK;
}

static int disp_reposition(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int x, y;
    if (ms_arg_int(interp, objv[2], "x", INT_MIN, INT_MAX, &x) ||
        ms_arg_int(interp, objv[3], "y", INT_MIN, INT_MAX, &y))
        return TCL_ERROR;
    return TCL_OK;   /* no window to move */
}

static int disp_size(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc > 2)   /* what VMD users may try: say what to use instead */
        return ms_cmd_error(interp, "display size: the size is read-only here; use display resize <w> <h>");
    Tcl_SetObjResult(interp, get_word(app, "size"));
    return TCL_OK;
}

static int disp_resetview(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_view_reset(&app->world);
    return TCL_OK;
}

static int disp_update(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = objc == 2 ? "ui" : Tcl_GetString(objv[2]);
    int b;
    if (ms_word_eq(w, "ui")) {
        /* a redraw (and, with ui, the interface's turn, which has nothing more to do here):
         * the frames still being read arrive now, and rocking advances, as in VMD's loop */
        ms_app_finish_loading(app);
        ms_view_rock_step(&app->world);
    } else if (ms_word_eq(w, "status")) Tcl_SetObjResult(interp, Tcl_NewIntObj(app->world.view->update));
    else if (ms_arg_bool(NULL, objv[2], NULL, &b) == TCL_OK) app->world.view->update = b;
    else return ms_args_usage(interp);
    return TCL_OK;
}

/* ---------------------------------------------------------------- axes, stage */

static int axes_location(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int l;
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_axes_loc_name(app->world.view->axes), -1));
        return TCL_OK;
    }
    if (pick(interp, objv[2], axes_name, MS_AXES_NLOCS, "location", &l)) return TCL_ERROR;
    app->world.view->axes = (ms_axes_loc)l;
    return TCL_OK;
}

static int axes_locations(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < MS_AXES_NLOCS; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_axes_loc_name((ms_axes_loc)i), -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int stage_location(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int l;
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_stage_loc_name(app->world.view->stage), -1));
        return TCL_OK;
    }
    if (pick(interp, objv[2], stage_name, MS_STAGE_NLOCS, "location", &l)) return TCL_ERROR;
    app->world.view->stage = (ms_stage_loc)l;
    return TCL_OK;
}

static int stage_locations(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < MS_STAGE_NLOCS; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_stage_loc_name((ms_stage_loc)i), -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int stage_panels(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(app->world.view->stage_panels));
        return TCL_OK;
    }
    return ms_arg_int(interp, objv[2], NULL, 1, 30, &app->world.view->stage_panels);
}

static int stage_size(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    float s;
    if (objc == 2) {
        Tcl_SetObjResult(interp, ms_cmd_float_obj(app->world.view->stage_size));
        return TCL_OK;
    }
    if (ms_arg_float(interp, objv[2], NULL, &s)) return TCL_ERROR;
    if (s <= 0) return ms_cmd_error(interp, "stage size: %g must be positive", s);
    app->world.view->stage_size = s;
    return TCL_OK;
}

/* ---------------------------------------------------------------- light */

/* light <n> ...: the light, checked by light_n before its word is dispatched */
static ms_light *the_light(ms_app *app, Tcl_Obj *const objv[], int *n)
{
    Tcl_GetIntFromObj(NULL, objv[1], n);
    return &app->world.view->settings.lights[*n];
}

static int light_switch(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int n;
    ms_light *l = the_light(app, objv, &n);
    const char *w = Tcl_GetString(objv[2]);
    if (ms_word_eq(w, "on") || ms_word_eq(w, "off")) l->on = ms_word_eq(w, "on");
    else app->world.view->light_highlight[n] = ms_word_eq(w, "highlight");
    return TCL_OK;
}

static int light_status(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int n;
    ms_light *l = the_light(app, objv, &n);
    Tcl_SetObjResult(interp, Tcl_ObjPrintf("%s %s", l->on ? "on" : "off",
                                           app->world.view->light_highlight[n] ? "highlight" : "unhighlight"));
    return TCL_OK;
}

static int light_pos(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int n;
    ms_light *l = the_light(app, objv, &n);
    if (objc == 3) {
        Tcl_SetObjResult(interp, vec_obj(l->pos));
        return TCL_OK;
    }
    if (ms_word_eq(Tcl_GetString(objv[3]), "default")) {
        /* as VMD: reports the default position (the caller sets it if it wants) */
        Tcl_SetObjResult(interp, vec_obj(ms_view_default_light(n)));
        return TCL_OK;
    }
    return ms_arg_vec3(interp, objv[3], NULL, l->pos);
}

static int light_rot(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const axes[] = {"x", "y", "z", NULL};
    int n, ax;
    ms_light *l = the_light(app, objv, &n);
    float deg, r[16];
    if (ms_arg_choice(interp, objv[3], axes, "axis", &ax) ||
        ms_arg_float(interp, objv[4], "angle", &deg))
        return TCL_ERROR;
    ms_mat4_axis_rotation(r, "xyz"[ax], ms_deg_rad(deg));
    ms_mat4_point(r, l->pos, l->pos);
    return TCL_OK;
}

/* light <n> <word> ...: the light's number, then its subcommand */
static int light_n(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd words[] = {
        {"on", light_switch, 0, 0, ""},
        {"off", light_switch, 0, 0, ""},
        {"highlight", light_switch, 0, 0, ""},
        {"unhighlight", light_switch, 0, 0, ""},
        {"status", light_status, 0, 0, ""},
        {"pos", light_pos, 0, 1, "?{x y z}|default?"},
        {"rot", light_rot, 2, 2, "<axis> <degrees>"},
        {NULL, NULL, 0, 0, NULL}};
    int n;
    if (ms_arg_int(interp, objv[1], "light", INT_MIN, INT_MAX, &n)) return TCL_ERROR;
    if (n < 0 || n >= MS_SCENE_LIGHTS)
        return ms_cmd_error(interp, "light: no light %d (lights are 0 to %d)", n, MS_SCENE_LIGHTS - 1);
    char where[32];
    snprintf(where, sizeof where, "light %d", n);
    return ms_args_dispatch(app, interp, objc, objv, 2, words, NULL, where);
}

static int light_num(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(MS_SCENE_LIGHTS));
    return TCL_OK;
}

/* ---------------------------------------------------------------- registration */

static const ms_subcmd display_table[] = {
    {"resetview", disp_resetview, 0, 0, ""},
    {"update", disp_update, 0, 1, "?on|off|status|ui?"},
    {"resize", disp_resize, 2, 2, "<width> <height>"},
    {"reposition", disp_reposition, 2, 2, "<x> <y>"},
    {"size", disp_size, 0, MS_ARGS_ANY, ""},
    {"nearclip", disp_clip, 0, 2, "?set|add <value>?"},
    {"farclip", disp_clip, 0, 2, "?set|add <value>?"},
    {"projection", disp_choice, 0, 1, "?Perspective|Orthographic?"},
    {"proj", disp_choice, 0, 1, "?Perspective|Orthographic?"},
    {"cuemode", disp_choice, 0, 1, "?Linear|Exp|Exp2?"},
    {"stereo", disp_choice, 0, 1, "?<mode>?"},
    {"rendermode", disp_choice, 0, 1, "?<mode>?"},
    {"cachemode", disp_choice, 0, 1, "?<mode>?"},
    {NULL, NULL, 0, 0, NULL}};

static const ms_subcmd axes_table[] = {
    {"location", axes_location, 0, 1, "?<location>?"},
    {"locations", axes_locations, 0, 0, ""},
    {NULL, NULL, 0, 0, NULL}};

static const ms_subcmd stage_table[] = {
    {"location", stage_location, 0, 1, "?<location>?"},
    {"locations", stage_locations, 0, 0, ""},
    {"panels", stage_panels, 0, 1, "?<n>?"},
    {"size", stage_size, 0, 1, "?<size>?"},
    {NULL, NULL, 0, 0, NULL}};

static const ms_subcmd light_table[] = {{"num", light_num, 0, 0, ""}, {NULL, NULL, 0, 0, NULL}};

void ms_cmd_display_register(ms_app *app)
{
    static const ms_subcmd queries[] = {{"get", disp_get, 1, 1, "<setting>"},
                                        {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd light_fallback = {
        "<n>", light_n, 2, 4, "<n> on|off|highlight|unhighlight|status | <n> pos ?{x y z}|default? "
                              "| <n> rot <axis> <degrees>"};
    ms_cmdset_create(app, "display", display_table);
    ms_cmdset_extend_quiet(app, "display", queries);
    ms_subcmd one[2] = {{NULL, disp_setting, 0, 1, "?<value>?"}, {NULL, NULL, 0, 0, NULL}};
    for (size_t i = 0; i < MS_COUNTOF(settings); i++) {
        one[0].name = settings[i].name;
        ms_cmdset_extend(app, "display", one);
    }
    ms_cmdset_create(app, "axes", axes_table);
    ms_cmdset_create(app, "stage", stage_table);
    ms_cmdset_create(app, "light", light_table);
    ms_cmdset_fallback(app, "light", &light_fallback);
}
