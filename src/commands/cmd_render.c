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
#include "render/render.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const ms_render_device *get_device(Tcl_Interp *interp, Tcl_Obj *o, const char *cmd)
{
    const ms_render_device *d = ms_render_find(Tcl_GetString(o));
    if (!d) ms_cmd_error(interp, "%s: no render method '%s' (see render list)", cmd, Tcl_GetString(o));
    return d;
}

/* Words from objv[from] on joined with spaces (a Tcl_Obj with refcount 0). */
static Tcl_Obj *joined(int objc, Tcl_Obj *const objv[], int from)
{
    Tcl_Obj *s = Tcl_NewObj();
    for (int i = from; i < objc; i++) {
        if (i > from) Tcl_AppendToObj(s, " ", 1);
        Tcl_AppendObjToObj(s, objv[i]);
    }
    return s;
}

static ms_render_setting *setting(ms_app *app, Tcl_Interp *interp, const ms_render_device *d)
{
    ms_render_setting *s = ms_render_setting_of(app->renderers, d);
    if (!s) ms_cmd_error(interp, "render: out of memory");
    return s;
}

/* Tachyon's image formats: the post-render command follows the chosen format, as VMD's. */
static const char *const tachyon_formats[][2] = {
    {"BMP", "bmp"}, {"PPM", "ppm"}, {"PPM48", "ppm"}, {"PSD48", "psd"}, {"RGB", "rgb"},
    {"TARGA", "tga"}};

static void tachyon_cmd_text(const ms_render_setting *s, int format, char *buf, size_t size)
{
    const char *bin = getenv("TACHYON_BIN");
    snprintf(buf, size, "%s -aasamples %d %%s -format %s -o %%s.%s",
             bin && *bin ? bin : "tachyon", s->aasamples, tachyon_formats[format][0],
             tachyon_formats[format][1]);
}

static int tachyon_cmd(ms_render_setting *s, int format)
{
    char buf[1024];
    tachyon_cmd_text(s, format, buf, sizeof buf);
    return ms_render_set_cmd(s, buf);
}

static int tachyon_format_of(const ms_render_setting *s)
{
    for (int i = 0; i < (int)MS_COUNTOF(tachyon_formats); i++) {
        char key[32];
        snprintf(key, sizeof key, "-format %s ", tachyon_formats[i][0]);
        if (strstr(s->cmd, key)) return i;
    }
    return 5;
}

static int is_tachyon(const ms_render_device *d)
{
    return !strcmp(d->name, "Tachyon");
}

static int r_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < ms_render_count(); i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(ms_render_device_at(i)->name, -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int r_options(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    if (objc < 3) return ms_cmd_error(interp, "render %s: usage: render %s <method>", w, w);
    const ms_render_device *d = get_device(interp, objv[2], "render");
    ms_render_setting *s = d ? setting(app, interp, d) : NULL;
    if (!s) return TCL_ERROR;
    if (ms_word_eq(w, "default")) {
        if (objc != 3) return ms_cmd_error(interp, "render default: usage: render default <method>");
        Tcl_SetObjResult(interp, Tcl_NewStringObj(d->default_cmd, -1));
        return TCL_OK;
    }
    if (objc == 3) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(s->cmd, -1));
        return TCL_OK;
    }
    Tcl_Obj *cmd = joined(objc, objv, 3);
    Tcl_IncrRefCount(cmd);
    int rc = ms_render_set_cmd(s, Tcl_GetString(cmd));
    Tcl_DecrRefCount(cmd);
    return rc ? ms_cmd_error(interp, "render options: out of memory") : TCL_OK;
}

static int r_samples(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    int ao = ms_word_eq(w, "aosamples");
    if (objc != 3 && objc != 4) return ms_cmd_error(interp, "render %s: usage: render %s <method> ?<n>?", w, w);
    const ms_render_device *d = get_device(interp, objv[2], "render");
    ms_render_setting *s = d ? setting(app, interp, d) : NULL;
    if (!s) return TCL_ERROR;
    if (objc == 4) {
        long n;
        char what[32], gen[1024];
        snprintf(what, sizeof what, "render %s", ao ? "aosamples" : "aasamples");
        if (ms_cmd_get_count(interp, objv[3], 65536, what, &n)) return TCL_ERROR;
        /* Tachyon's post-render command names the samples: keep it in step, unless the
         * user has replaced it */
        int fmt = is_tachyon(d) ? tachyon_format_of(s) : 0, follow = 0;
        if (is_tachyon(d) && !ao) {
            tachyon_cmd_text(s, fmt, gen, sizeof gen);
            follow = !strcmp(gen, s->cmd);
        }
        if (ao) s->aosamples = (int)n;
        else s->aasamples = (int)n;
        if (follow && tachyon_cmd(s, fmt)) return ms_cmd_error(interp, "render: out of memory");
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(ao ? s->aosamples : s->aasamples));
    return TCL_OK;
}

static int r_info(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    if (objc != 3) return ms_cmd_error(interp, "render %s: usage: render %s <method>", w, w);
    const ms_render_device *d = get_device(interp, objv[2], "render");
    if (!d) return TCL_ERROR;
    if (ms_word_eq(w, "hasaa")) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(d->has_aa));
    } else if (ms_word_eq(w, "imagesize")) {
        Tcl_SetObjResult(interp, Tcl_ObjPrintf("%d %d", app->width, app->height));
    } else if (ms_word_eq(w, "aspectratio")) {
        Tcl_SetObjResult(interp, Tcl_NewDoubleObj((double)app->width / app->height));
    } else {   /* formats */
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (size_t i = 0; is_tachyon(d) && i < MS_COUNTOF(tachyon_formats); i++)
            Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(tachyon_formats[i][0], -1));
        Tcl_SetObjResult(interp, l);
    }
    return TCL_OK;
}

static int r_format(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc != 3 && objc != 4) return ms_cmd_error(interp, "render format: usage: render format <method> ?<format>?");
    const ms_render_device *d = get_device(interp, objv[2], "render format");
    ms_render_setting *s = d ? setting(app, interp, d) : NULL;
    if (!s) return TCL_ERROR;
    if (!is_tachyon(d)) {
        if (objc == 3) return TCL_OK;
        return ms_cmd_error(interp, "render format: %s has no output formats", d->name);
    }
    if (objc == 3) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(tachyon_formats[tachyon_format_of(s)][0], -1));
        return TCL_OK;
    }
    const char *f = Tcl_GetString(objv[3]);
    for (int i = 0; i < (int)MS_COUNTOF(tachyon_formats); i++)
        if (!strcasecmp(f, tachyon_formats[i][0]) || (i == 5 && !strcasecmp(f, "TGA")))
            return tachyon_cmd(s, i) ? ms_cmd_error(interp, "render format: out of memory") : TCL_OK;
    return ms_cmd_error(interp, "render format: unknown format '%s' for %s", f, d->name);
}

/* render <method> <file> ?cmd...? */
static int r_render(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc < 3)
        return ms_cmd_error(interp, "render: usage: render list | render <method> <file> ?<command>?");
    const ms_render_device *d = get_device(interp, objv[1], "render");
    if (!d) return TCL_ERROR;
    Tcl_Obj *cmd = joined(objc, objv, 3);
    Tcl_IncrRefCount(cmd);
    ms_error err = {{0}};
    int rc = ms_render(app, d, Tcl_GetString(objv[2]), Tcl_GetString(cmd), &err);
    Tcl_DecrRefCount(cmd);
    if (rc) return ms_cmd_error(interp, "render %s: %s", d->name, err.msg);
    return TCL_OK;
}

static const ms_subcmd render_table[] = {
    {"list", r_list}, {"options", r_options}, {"default", r_options}, {"aasamples", r_samples},
    {"aosamples", r_samples}, {"hasaa", r_info}, {"imagesize", r_info}, {"aspectratio", r_info},
    {"formats", r_info}, {"format", r_format}, {NULL, NULL}};

void ms_cmd_render_register(ms_app *app)
{
    ms_cmdset_create(app, "render", render_table);
    ms_cmdset_fallback(app, "render", r_render);
}
