/* cmd_color.c: the `color` and `colorinfo` commands.
 *
 *   color <category> <item> ?color?          get or set an item's colour
 *   color change rgb <color> ?r g b | gray?  change a colour (no value: restore its default)
 *   color change rgblist {{r g b} ...} | {{color r g b} ...}
 *   color change namelist {{category item color} ...}
 *   color scale method|midpoint|min|max <v>;  color scale colors <method> ?c1 c2 c3?
 *   color restype <resname> ?type?;  color add item <category> <item> <color>
 *   colorinfo categories | category <cat> ?item? | num | max | colors | index <c> | rgb <c>
 *   colorinfo scale method|methods|midpoint|min|max
 * Every failure leaves the colours unchanged. */
#include "config.h"
#include "commands/scenecmds.h"
#include "scene/color.h"

#include <string.h>

static int get_color(ms_app *app, Tcl_Interp *interp, Tcl_Obj *o, const char *cmd, int *id)
{
    *id = ms_color_index(app->world.colors, Tcl_GetString(o));
    if (*id < 0) return ms_cmd_error(interp, "%s: unknown color '%s'", cmd, Tcl_GetString(o));
    return TCL_OK;
}

static int get_category(ms_app *app, Tcl_Interp *interp, Tcl_Obj *o, const char *cmd, int *cat)
{
    *cat = ms_color_category_index(app->world.colors, Tcl_GetString(o));
    if (*cat < 0)
        return ms_cmd_error(interp, "%s: unknown color category '%s'", cmd, Tcl_GetString(o));
    return TCL_OK;
}

static Tcl_Obj *color_obj(int id)
{
    const char *name = ms_color_name(id);
    return name ? Tcl_NewStringObj(name, -1) : Tcl_NewIntObj(id);
}

static Tcl_Obj *rgb_obj(const float rgb[3])
{
    Tcl_Obj *v[3];
    for (int k = 0; k < 3; k++) v[k] = Tcl_NewDoubleObj(rgb[k]);
    return Tcl_NewListObj(3, v);
}

/* An {r g b} list or a colour name. */
static int get_rgb(ms_app *app, Tcl_Interp *interp, Tcl_Obj *o, const char *cmd, float rgb[3])
{
    int id = ms_color_index(app->world.colors, Tcl_GetString(o));
    if (id >= 0 && !strchr(Tcl_GetString(o), ' ')) {
        memcpy(rgb, ms_color_rgb(app->world.colors, id), 3 * sizeof(float));
        return TCL_OK;
    }
    return ms_arg_vec3(interp, o, NULL, rgb);
}

/* ---------------------------------------------------------------- color change */

static int change_rgb(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = "color change rgb";
    if (objc == 6) return ms_args_usage(interp);
    int id;
    if (get_color(app, interp, objv[3], cmd, &id)) return TCL_ERROR;
    float rgb[3];
    if (objc == 4) {
        ms_color_default_rgb(id, rgb);
    } else {
        for (int k = 0; k < 3; k++)
            if (ms_arg_float(interp, objv[objc == 5 ? 4 : 4 + k], NULL, &rgb[k])) return TCL_ERROR;
    }
    ms_color_set_rgb(app->world.colors, id, rgb);
    return TCL_OK;
}

/* {{r g b} ...} sets colours 0, 1, ...; {{name r g b} ...} or {{name {r g b}} ...} by name. */
static int change_rgblist(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = "color change rgblist";
    Tcl_Obj *list = objv[3];
    Tcl_Obj **e;
    int n;
    if (Tcl_ListObjGetElements(NULL, list, &n, &e) != TCL_OK)
        return ms_cmd_error(interp, "%s: expected a list, got '%s'", cmd, Tcl_GetString(list));
    int ids[MS_COLOR_NUM];
    float rgb[MS_COLOR_NUM][3];
    if (n > MS_COLOR_NUM) return ms_cmd_error(interp, "%s: %d entries for %d colors", cmd, n, MS_COLOR_NUM);
    for (int i = 0; i < n; i++) {
        Tcl_Obj **f;
        int m;
        if (Tcl_ListObjGetElements(NULL, e[i], &m, &f) != TCL_OK) m = 0;
        if (m == 3) {
            ids[i] = i;
            if (ms_arg_vec3(interp, e[i], NULL, rgb[i])) return TCL_ERROR;
        } else if (m == 2 || m == 4) {
            if (get_color(app, interp, f[0], cmd, &ids[i])) return TCL_ERROR;
            Tcl_Obj *v = m == 2 ? f[1] : Tcl_NewListObj(3, f + 1);
            if (ms_arg_vec3(interp, v, NULL, rgb[i])) return TCL_ERROR;
        } else {
            return ms_cmd_error(interp, "%s: bad entry '%s': expected {r g b} or {color r g b}",
                                cmd, Tcl_GetString(e[i]));
        }
    }
    for (int i = 0; i < n; i++) ms_color_set_rgb(app->world.colors, ids[i], rgb[i]);
    return TCL_OK;
}

static int change_namelist(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = "color change namelist";
    Tcl_Obj *list = objv[3];
    Tcl_Obj **e;
    int n;
    if (Tcl_ListObjGetElements(NULL, list, &n, &e) != TCL_OK)
        return ms_cmd_error(interp, "%s: expected a list, got '%s'", cmd, Tcl_GetString(list));
    /* check everything first: all or nothing */
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < n; i++) {
            Tcl_Obj **f;
            int m, cat, col;
            if (Tcl_ListObjGetElements(NULL, e[i], &m, &f) != TCL_OK || m != 3)
                return ms_cmd_error(interp, "%s: bad entry '%s': expected {category item color}",
                                    cmd, Tcl_GetString(e[i]));
            if (get_category(app, interp, f[0], cmd, &cat) || get_color(app, interp, f[2], cmd, &col))
                return TCL_ERROR;
            if (pass == 0 && ms_color_item_index(app->world.colors, cat, Tcl_GetString(f[1])) < 0)
                return ms_cmd_error(interp, "%s: category %s has no item '%s'", cmd,
                                    Tcl_GetString(f[0]), Tcl_GetString(f[1]));
            if (pass == 1) ms_color_item_set(app->world.colors, cat, Tcl_GetString(f[1]), col);
        }
    return TCL_OK;
}

static int color_change(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd table[] = {
        {"rgb", change_rgb, 1, 4, "<color> ?<gray> | <r> <g> <b>?"},
        {"rgblist", change_rgblist, 1, 1, "{{r g b} ...} | {{<color> r g b} ...}"},
        {"namelist", change_namelist, 1, 1, "{{<category> <item> <color>} ...}"},
        {NULL, NULL, 0, 0, NULL}};
    return ms_args_dispatch(app, interp, objc, objv, 2, table, NULL, NULL);
}

/* ---------------------------------------------------------------- color scale */

static int scale_colors(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = "color scale colors";
    if (objc != 4 && objc != 7) return ms_args_usage(interp);
    int m = ms_color_scale_method_index(app->world.colors, Tcl_GetString(objv[3]));
    if (m < 0)
        return ms_cmd_error(interp, "%s: unknown color scale method '%s'", cmd, Tcl_GetString(objv[3]));
    if (objc == 4) {
        Tcl_Obj *v[3];
        for (int i = 0; i < 3; i++) v[i] = rgb_obj(app->world.colors->methods[m].rgb[i]);
        Tcl_SetObjResult(interp, Tcl_NewListObj(3, v));
        return TCL_OK;
    }
    float rgb[3][3];
    for (int i = 0; i < 3; i++)
        if (get_rgb(app, interp, objv[4 + i], cmd, rgb[i])) return TCL_ERROR;
    ms_color_scale_set_colors(app->world.colors, m, rgb);
    return TCL_OK;
}

/* The scale's settings, as colorinfo scale and the setters without a value answer them. */
static const char *const scale_words[] = {"method", "methods", "midpoint", "min", "max", NULL};

static int scale_answer(ms_app *app, Tcl_Interp *interp, int w)
{
    const ms_colors *c = app->world.colors;
    if (w == 0) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(c->methods[c->method].name, -1));
    } else if (w == 1) {
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (int i = 0; i < MS_COLOR_SCALE_METHODS; i++)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(c->methods[i].name, -1));
        Tcl_SetObjResult(interp, l);
    } else {
        Tcl_SetObjResult(interp, Tcl_NewDoubleObj(w == 2 ? c->scale_mid : w == 3 ? c->scale_min
                                                                               : c->scale_max));
    }
    return TCL_OK;
}

static int scale_method(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 3) return scale_answer(app, interp, 0);
    int m = ms_color_scale_method_index(app->world.colors, Tcl_GetString(objv[3]));
    if (m < 0)
        return ms_cmd_error(interp, "color scale method: unknown method '%s'", Tcl_GetString(objv[3]));
    ms_color_scale_set_method(app->world.colors, m);
    return TCL_OK;
}

/* midpoint, min, max */
static int scale_value(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_colors *c = app->world.colors;
    const char *what = Tcl_GetString(objv[2]);
    float v, mid = c->scale_mid, min = c->scale_min, max = c->scale_max;
    if (objc == 3) return scale_answer(app, interp, ms_args_find(scale_words, sizeof *scale_words, what));
    if (ms_arg_float(interp, objv[3], NULL, &v)) return TCL_ERROR;
    if (ms_word_eq(what, "midpoint")) {
        if (v < 0 || v > 1)
            return ms_cmd_error(interp, "color scale midpoint: %g is outside 0..1", v);
        mid = v;
    } else if (ms_word_eq(what, "min")) {
        min = v;
    } else {
        max = v;
    }
    ms_color_scale_set_values(c, mid, min, max);
    return TCL_OK;
}

static int color_scale(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd table[] = {
        {"method", scale_method, 0, 1, "?<method>?"},
        {"midpoint", scale_value, 0, 1, "?<0..1>?"},
        {"min", scale_value, 0, 1, "?<value>?"},
        {"max", scale_value, 0, 1, "?<value>?"},
        {"colors", scale_colors, 1, 4, "<method> ?<low> <mid> <high>?"},
        {NULL, NULL, 0, 0, NULL}};
    return ms_args_dispatch(app, interp, objc, objv, 2, table, NULL, NULL);
}

/* ---------------------------------------------------------------- the rest */

/* color restype <resname> ?type?. `color Restype <type> ?color?` (the category, which the
 * subcommand word shadows) also works, as it does in VMD. */
static int color_item(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);

static int color_restype(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *res = Tcl_GetString(objv[2]);
    int cat = ms_color_category_index(app->world.colors, "Restype");
    int is_item = ms_color_item_index(app->world.colors, cat, res) >= 0;
    if (objc == 3) {
        const char *t = ms_color_restype(app->world.colors, res);
        if (!t && is_item) return color_item(app, interp, objc, objv);
        if (!t) return ms_cmd_error(interp, "color restype: no restype for residue '%s'", res);
        Tcl_SetObjResult(interp, Tcl_NewStringObj(t, -1));
        return TCL_OK;
    }
    if (ms_color_set_restype(app->world.colors, res, Tcl_GetString(objv[3])) == 0) return TCL_OK;
    if (is_item && ms_color_index(app->world.colors, Tcl_GetString(objv[3])) >= 0)
        return color_item(app, interp, objc, objv);
    return ms_cmd_error(interp, "color restype: unknown residue type '%s'", Tcl_GetString(objv[3]));
}

static int add_item(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int cat, col;
    if (get_category(app, interp, objv[3], "color add item", &cat) ||
        get_color(app, interp, objv[5], "color add item", &col))
        return TCL_ERROR;
    if (ms_color_item_add(app->world.colors, cat, Tcl_GetString(objv[4]), col) < 0)
        return ms_cmd_error(interp, "color add item: out of memory");
    return TCL_OK;
}

static int color_add(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd table[] = {{"item", add_item, 3, 3, "<category> <item> <color>"},
                                      {NULL, NULL, 0, 0, NULL}};
    return ms_args_dispatch(app, interp, objc, objv, 2, table, NULL, NULL);
}

/* color <category> <item> ?color? */
static int color_item(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int cat, col;
    if (get_category(app, interp, objv[1], "color", &cat)) return TCL_ERROR;
    const char *item = Tcl_GetString(objv[2]);
    if (ms_color_item_index(app->world.colors, cat, item) < 0)
        return ms_cmd_error(interp, "color: category %s has no item '%s'", Tcl_GetString(objv[1]), item);
    if (objc == 3) {
        Tcl_SetObjResult(interp, color_obj(ms_color_item_get(app->world.colors, cat, item)));
        return TCL_OK;
    }
    if (get_color(app, interp, objv[3], "color", &col)) return TCL_ERROR;
    ms_color_item_set(app->world.colors, cat, item, col);
    return TCL_OK;
}

/* ---------------------------------------------------------------- colorinfo */

static int info_categories(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < app->world.colors->ncats; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(app->world.colors->cats[i].name, -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int info_category(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int cat;
    if (get_category(app, interp, objv[2], "colorinfo category", &cat)) return TCL_ERROR;
    const ms_color_category *k = &app->world.colors->cats[cat];
    if (objc == 4) {
        int col = ms_color_item_get(app->world.colors, cat, Tcl_GetString(objv[3]));
        if (col < 0)
            return ms_cmd_error(interp, "colorinfo category: category %s has no item '%s'",
                                k->name, Tcl_GetString(objv[3]));
        Tcl_SetObjResult(interp, color_obj(col));
        return TCL_OK;
    }
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < k->n; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(k->items[i].name, -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int info_num(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(MS_COLOR_NUM));
    return TCL_OK;
}

static int info_max(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(MS_COLOR_MAX));
    return TCL_OK;
}

static int info_colors(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < MS_COLOR_NUM; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_color_name(i), -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int info_index_rgb(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *what = Tcl_GetString(objv[1]);
    int id;
    if (get_color(app, interp, objv[2], "colorinfo", &id)) return TCL_ERROR;
    Tcl_SetObjResult(interp, ms_word_eq(what, "index") ? Tcl_NewIntObj(id)
                                                        : rgb_obj(ms_color_rgb(app->world.colors, id)));
    return TCL_OK;
}

static int info_scale(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int w;
    if (ms_arg_choice(interp, objv[2], scale_words, NULL, &w)) return TCL_ERROR;
    return scale_answer(app, interp, w);
}

static const ms_subcmd color_table[] = {
    {"change", color_change, 1, MS_ARGS_ANY, "rgb|rgblist|namelist ..."},
    {"scale", color_scale, 1, MS_ARGS_ANY, "method|midpoint|min|max|colors ..."},
    {"restype", color_restype, 1, 2, "<resname> ?<type>?"},
    {"add", color_add, 1, MS_ARGS_ANY, "item <category> <item> <color>"},
    {NULL, NULL, 0, 0, NULL}};

static const ms_subcmd colorinfo_table[] = {
    {"categories", info_categories, 0, 0, ""},
    {"category", info_category, 1, 2, "<category> ?<item>?"},
    {"num", info_num, 0, 0, ""},
    {"max", info_max, 0, 0, ""},
    {"colors", info_colors, 0, 0, ""},
    {"index", info_index_rgb, 1, 1, "<color>"},
    {"rgb", info_index_rgb, 1, 1, "<color>"},
    {"scale", info_scale, 1, 1, "method|methods|midpoint|min|max"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_color_register(ms_app *app)
{
    static const ms_subcmd by_category = {"<category>", color_item, 2, 3,
                                          "<category> <item> ?<color>?"};
    ms_cmdset_create(app, "color", color_table);
    ms_cmdset_fallback(app, "color", &by_category);
    ms_cmdset_create(app, "colorinfo", colorinfo_table);
    ms_cmdset_quiet(app, "colorinfo");
}
