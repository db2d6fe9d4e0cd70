/* cmd_render.c: the `render` command.
 *
 *   render list                                  the device names
 *   render <method> <file> ?cmd...?              write the scene; then run cmd (words joined
 *                                                with spaces; %s file, %w %h display size)
 *   render options <method> ?cmd...?             get or set the device's post-render command
 *   render default <method>                      VMD's default post-render command
 *   render hasaa <method>;  render aasamples|aosamples <method> ?n?
 *   render imagesize <method>;  render aspectratio <method>
 *   render formats <method>;  render format <method> ?fmt? */
#include "config.h"
#include "commands/scenecmds.h"
#include "assemble/devices.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A device by name, or the one standing in for an engine of VMD's molscope lacks (with a
 * one-line note when it renders). */
static const ms_render_device *find_device(Tcl_Interp *interp, Tcl_Obj *o, const char *cmd,
                                           int note)
{
    const char *name = Tcl_GetString(o);
    const ms_render_device *d = ms_render_find(name);
    if (d) return d;
    if ((d = ms_render_find_alias(name))) {
        if (note) {
            printf("Info) render: %s is not built into molscope; rendering with %s\n", name,
                   d->name);
            fflush(stdout);
        }
        return d;
    }
    ms_cmd_error(interp, "%s: no render method '%s' (see render list)", cmd, name);
    return NULL;
}

static const ms_render_device *get_device(Tcl_Interp *interp, Tcl_Obj *o, const char *cmd)
{
    return find_device(interp, o, cmd, 0);
}

static ms_render_setting *setting(ms_app *app, Tcl_Interp *interp, const ms_render_device *d)
{
    ms_render_setting *s = ms_render_setting_of(app->world.renderers, d);
    if (!s) ms_cmd_error(interp, "render: out of memory");
    return s;
}

static int r_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < ms_render_count(); i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_render_device_at(i)->name, -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int r_default(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const ms_render_device *d = get_device(interp, objv[2], "render");
    if (!d || !setting(app, interp, d)) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewStringObj(d->default_cmd, -1));
    return TCL_OK;
}

static int r_options(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const ms_render_device *d = get_device(interp, objv[2], "render");
    ms_render_setting *s = d ? setting(app, interp, d) : NULL;
    if (!s) return TCL_ERROR;
    if (objc == 3) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(s->cmd, -1));
        return TCL_OK;
    }
    Tcl_Obj *cmd = ms_args_joined(objc, objv, 3);
    Tcl_IncrRefCount(cmd);
    int rc = ms_render_set_cmd(s, Tcl_GetString(cmd));
    Tcl_DecrRefCount(cmd);
    return rc ? ms_cmd_error(interp, "render options: out of memory") : TCL_OK;
}

static int r_samples(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int ao = ms_word_eq(Tcl_GetString(objv[1]), "aosamples");
    const ms_render_device *d = get_device(interp, objv[2], "render");
    ms_render_setting *s = d ? setting(app, interp, d) : NULL;
    if (!s) return TCL_ERROR;
    if (objc == 4) {
        long n;
        if (ms_arg_long(interp, objv[3], NULL, 0, 65536, &n)) return TCL_ERROR;
        if (ms_render_set_samples(s, ao ? -1 : (int)n, ao ? (int)n : -1))
            return ms_cmd_error(interp, "render: out of memory");
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(ao ? s->aosamples : s->aasamples));
    return TCL_OK;
}

static int r_info(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    const ms_render_device *d = get_device(interp, objv[2], "render");
    if (!d) return TCL_ERROR;
    if (ms_word_eq(w, "hasaa")) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(d->has_aa));
    } else if (ms_word_eq(w, "imagesize")) {
        Tcl_SetObjResult(interp, Tcl_ObjPrintf("%d %d", app->world.width, app->world.height));
    } else if (ms_word_eq(w, "aspectratio")) {
        Tcl_SetObjResult(interp, Tcl_NewDoubleObj((double)app->world.width / app->world.height));
    } else {   /* formats */
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (const char *const *f = d->formats; f && *f; f++)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(*f, -1));
        Tcl_SetObjResult(interp, l);
    }
    return TCL_OK;
}

static int r_format(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const ms_render_device *d = get_device(interp, objv[2], "render format");
    ms_render_setting *s = d ? setting(app, interp, d) : NULL;
    if (!s) return TCL_ERROR;
    if (objc == 3) {
        if (d->formats) Tcl_SetObjResult(interp, Tcl_NewStringObj(d->formats[s->format], -1));
        return TCL_OK;
    }
    if (ms_render_set_format(s, Tcl_GetString(objv[3])))
        return ms_cmd_error(interp, "render format: unknown format '%s' for %s", Tcl_GetString(objv[3]), d->name);
    return TCL_OK;
}

/* render <method> <file> ?cmd...? */
static int r_render(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const ms_render_device *d = find_device(interp, objv[1], "render", 1);
    if (!d) return TCL_ERROR;
    Tcl_Obj *cmd = ms_args_joined(objc, objv, 3);
    Tcl_IncrRefCount(cmd);
    ms_error err = {{0}};
    int rc = ms_render(&app->world, d, Tcl_GetString(objv[2]), Tcl_GetString(cmd), &err);
    Tcl_DecrRefCount(cmd);
    if (rc) return ms_cmd_error(interp, "render %s: %s", d->name, err.msg);
    return TCL_OK;
}

static const ms_subcmd render_table[] = {
    {"list", r_list, 0, 0, ""},
    {"options", r_options, 1, MS_ARGS_ANY, "<method> ?<command> ...?"},
    {"default", r_default, 1, 1, "<method>"},
    {"aasamples", r_samples, 1, 2, "<method> ?<n>?"},
    {"aosamples", r_samples, 1, 2, "<method> ?<n>?"},
    {"hasaa", r_info, 1, 1, "<method>"},
    {"imagesize", r_info, 1, 1, "<method>"},
    {"aspectratio", r_info, 1, 1, "<method>"},
    {"formats", r_info, 1, 1, "<method>"},
    {"format", r_format, 1, 2, "<method> ?<format>?"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_render_register(ms_app *app)
{
    static const ms_subcmd by_method = {"<method>", r_render, 2, MS_ARGS_ANY,
                                        "<method> <file> ?<command> ...?"};
    ms_cmdset_create(app, "render", render_table);
    ms_cmdset_fallback(app, "render", &by_method);
    ms_cmdset_quiet(app, "render");
}
