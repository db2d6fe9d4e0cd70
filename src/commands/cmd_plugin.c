/* cmd_plugin.c: VMD's `plugin` command, answered from molscope's plugin registry
 * (fileio/registry.h). Every molscope file-format plugin is of VMD's type "mol file reader"
 * (it reads, and writes where it can, as VMD's molfile plugins do).
 *
 *   plugin list ?<type>?              {type name} pairs of the plugins known, in the order
 *                                     they were found (only those of type when given)
 *   plugin info <type> <name> <var>   1, filling the array var with type, name, author,
 *                                     majorversion, minorversion, reentrant (VMD's fields:
 *                                     molscope plugins name no author, their version is the
 *                                     plugin ABI they were built for) and molscope's
 *                                     description, extensions and filename;
 *                                     0 when there is no such plugin
 *   plugin dlopen <file>              load the plugin of a shared object: 1, or 0 when a
 *                                     plugin of its name is known already
 *   plugin update                     look in the plugin folders again for new ones */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PLUGIN_TYPE "mol file reader"

static int plugin_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *res = Tcl_NewListObj(0, NULL);
    if (objc == 3 && strcmp(Tcl_GetString(objv[2]), PLUGIN_TYPE) != 0) {
        Tcl_SetObjResult(interp, res);
        return TCL_OK;
    }
    for (size_t i = 0; i < app->plugins.n; i++) {
        Tcl_Obj *pair[2] = {Tcl_NewStringObj(PLUGIN_TYPE, -1),
                            Tcl_NewStringObj(app->plugins.plugins[i]->name, -1)};
        Tcl_ListObjAppendElement(NULL, res, Tcl_NewListObj(2, pair));
    }
    Tcl_SetObjResult(interp, res);
    return TCL_OK;
}

static int plugin_info(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    const ms_plugin *p = NULL;
    size_t i = 0;
    if (!strcmp(Tcl_GetString(objv[2]), PLUGIN_TYPE))
        for (; i < app->plugins.n && !p; i++)
            if (!strcmp(app->plugins.plugins[i]->name, Tcl_GetString(objv[3])))
                p = app->plugins.plugins[i];
    if (!p) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(0));
        return TCL_OK;
    }
    const char *var = Tcl_GetString(objv[4]);
    char abi[16];
    snprintf(abi, sizeof abi, "%d", p->abi);
    const char *fields[][2] = {
        {"type", PLUGIN_TYPE}, {"name", p->name}, {"author", ""},
        {"majorversion", abi}, {"minorversion", "0"}, {"reentrant", "1"},
        {"description", p->description ? p->description : ""},
        {"extensions", p->extensions ? p->extensions : ""},
        {"filename", app->plugins.paths[i - 1] ? app->plugins.paths[i - 1] : ""}};
    for (size_t k = 0; k < MS_COUNTOF(fields); k++)
        if (!Tcl_SetVar2(interp, var, fields[k][0], fields[k][1], TCL_LEAVE_ERR_MSG))
            return ms_cmd_error(interp, "plugin info: cannot set %s(%s): %s", var, fields[k][0],
                                Tcl_GetStringResult(interp));
    Tcl_SetObjResult(interp, Tcl_NewIntObj(1));
    return TCL_OK;
}

static int plugin_dlopen(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    ms_error err = {{0}};
    const char *path = Tcl_GetString(objv[2]);
    int rc = ms_registry_load_file(&app->plugins, path, &err);
    if (rc < 0)
        return strstr(err.msg, path) ? ms_cmd_error(interp, "plugin dlopen: %s", err.msg)
                                     : ms_cmd_error(interp, "plugin dlopen: %s: %s", path, err.msg);
    Tcl_SetObjResult(interp, Tcl_NewIntObj(rc));
    return TCL_OK;
}

static int plugin_update(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)interp, (void)objc, (void)objv;
    free(app->plugins.searched);   /* the folders are listed afresh */
    app->plugins.searched = NULL;
    ms_registry_load_default(&app->plugins, app->exe_path);
    return TCL_OK;
}

void ms_cmd_plugin_register(ms_app *app)
{
    static const ms_subcmd table[] = {
        {"list", plugin_list, 0, 1, "?<type>?"},
        {"info", plugin_info, 3, 3, "<type> <name> <varname>"},
        {"dlopen", plugin_dlopen, 1, 1, "<file>"},
        {"update", plugin_update, 0, 0, ""},
        {NULL, NULL, 0, 0, NULL}};
    ms_cmdset_create(app, "plugin", table);
}
