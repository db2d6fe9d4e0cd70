/* cmd_material.c: the `material` command.
 *
 *   material list                                    names, in order
 *   material settings <name>                         ambient specular diffuse shininess
 *                                                    mirror opacity outline outlinewidth
 *                                                    transmode (VMD's "%f" numbers)
 *   material add ?<name>? ?copy <from>?              -> the new material's name
 *   material rename <old> <new>;  material delete <name>
 *   material change <property> <name> <value>
 *   material default <name|index>                    restore a built-in material's values */
#include "config.h"
#include "commands/scenecmds.h"
#include "scene/material.h"

static int get_material(ms_app *app, Tcl_Interp *interp, Tcl_Obj *o, const char *cmd, int *i)
{
    *i = ms_material_index(app->world.materials, Tcl_GetString(o));
    if (*i < 0) return ms_cmd_error(interp, "%s: unknown material '%s'", cmd, Tcl_GetString(o));
    return TCL_OK;
}

static int mat_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < app->world.materials->n; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(app->world.materials->list[i].name, -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int mat_settings(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int i;
    if (get_material(app, interp, objv[2], "material settings", &i)) return TCL_ERROR;
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int p = 0; p < MS_MAT_NPROPS; p++)
        Tcl_ListObjAppendElement(NULL, l, ms_cmd_float_obj(
                                     ms_material_get(&app->world.materials->list[i], (ms_mat_prop)p)));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int mat_add(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const copy_word[] = {"copy", NULL};
    const char *name = objc == 3 || objc == 5 ? Tcl_GetString(objv[2]) : NULL;
    int from = 0, copy = objc == 4 ? 2 : objc == 5 ? 3 : -1, k;
    if (copy > 0) {
        if (ms_arg_choice(interp, objv[copy], copy_word, NULL, &k)) return TCL_ERROR;
        if (get_material(app, interp, objv[copy + 1], "material add", &from)) return TCL_ERROR;
    }
    ms_error err = {{0}};
    int i = ms_material_add(app->world.materials, name, from, &err);
    if (i < 0) return ms_cmd_error(interp, "material add: %s", err.msg);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(app->world.materials->list[i].name, -1));
    return TCL_OK;
}

static int mat_rename(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int i;
    if (get_material(app, interp, objv[2], "material rename", &i)) return TCL_ERROR;
    ms_error err = {{0}};
    if (ms_material_rename(app->world.materials, i, Tcl_GetString(objv[3]), &err))
        return ms_cmd_error(interp, "material rename: %s", err.msg);
    return TCL_OK;
}

static int mat_delete(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int i;
    if (get_material(app, interp, objv[2], "material delete", &i)) return TCL_ERROR;
    ms_error err = {{0}};
    if (ms_material_delete(app->world.materials, i, &err))
        return ms_cmd_error(interp, "material delete: %s", err.msg);
    return TCL_OK;
}

static int mat_change(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *props[MS_MAT_NPROPS + 1] = {NULL};
    for (int k = 0; k < MS_MAT_NPROPS; k++) props[k] = ms_material_prop_name((ms_mat_prop)k);
    int p, i;
    float v;
    if (ms_arg_choice(interp, objv[2], props, "property", &p) ||
        get_material(app, interp, objv[3], "material change", &i) ||
        ms_arg_float(interp, objv[4], NULL, &v))
        return TCL_ERROR;
    ms_material_set(app->world.materials, i, (ms_mat_prop)p, v);
    return TCL_OK;
}

static int mat_default(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int i;
    if (get_material(app, interp, objv[2], "material default", &i)) return TCL_ERROR;
    ms_error err = {{0}};
    if (ms_material_restore_default(app->world.materials, i, &err))
        return ms_cmd_error(interp, "material default: %s", err.msg);
    return TCL_OK;
}

static const ms_subcmd material_table[] = {
    {"list", mat_list, 0, 0, ""},
    {"settings", mat_settings, 1, 1, "<name>"},
    {"add", mat_add, 0, 3, "?<name>? ?copy <from>?"},
    {"rename", mat_rename, 2, 2, "<old> <new>"},
    {"delete", mat_delete, 1, 1, "<name>"},
    {"change", mat_change, 3, 3, "<property> <name> <value>"},
    {"default", mat_default, 1, 1, "<name|index>"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_material_register(ms_app *app)
{
    ms_cmdset_create(app, "material", material_table);
}
