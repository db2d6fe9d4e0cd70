/* cmd_trans.c: the transform commands, acting on every non-fixed molecule (assemble/view.h):
 *
 *   rotate x|y|z by|to <deg> ?<incr>?   rotate stop      (with incr VMD animates the turn;
 *                                                           here it is made at once)
 *   translate by|to <x> <y> <z>         scale by|to <s>  (s > 0)
 *   rock x|y|z by <deg> ?<steps>?       rock off          (advanced by `display update`)
 *   rotmat by|to <r11> ... <r33>        (nine numbers, taken column by column as VMD does) */
#include "config.h"
#include "commands/scenecmds.h"
#include "assemble/view.h"
#include "scene/mat4.h"

#include <string.h>
#include <strings.h>

static int get_axis(Tcl_Interp *interp, Tcl_Obj *o, const char *cmd, char *axis)
{
    const char *s = Tcl_GetString(o);
    if (strlen(s) != 1 || !strchr("xyzXYZ", s[0]))
        return ms_cmd_error(interp, "%s: unknown axis '%s': must be x, y or z", cmd, s);
    *axis = (char)(s[0] | 0x20);
    return TCL_OK;
}

/* "by" -> 1, "to" -> 0, else an error. */
static int get_by(Tcl_Interp *interp, Tcl_Obj *o, const char *cmd, int *by)
{
    const char *s = Tcl_GetString(o);
    if (!strcasecmp(s, "by")) *by = 1;
    else if (!strcasecmp(s, "to")) *by = 0;
    else return ms_cmd_error(interp, "%s: expected 'by' or 'to', got '%s'", cmd, s);
    return TCL_OK;
}

static int rotate_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_app *app = cd;
    if (objc == 2 && !strcasecmp(Tcl_GetString(objv[1]), "stop")) {
        ms_view_rock(&app->world, '\0', 0, 0);
        return TCL_OK;
    }
    if (objc != 4 && objc != 5)
        return ms_cmd_error(interp, "rotate: usage: rotate x|y|z by|to <angle> ?<increment>? | rotate stop");
    char axis;
    int by;
    float deg, incr;
    if (get_axis(interp, objv[1], "rotate", &axis) || get_by(interp, objv[2], "rotate", &by) ||
        ms_cmd_get_float(interp, objv[3], &deg, "rotate") ||
        (objc == 5 && ms_cmd_get_float(interp, objv[4], &incr, "rotate increment")))
        return TCL_ERROR;
    if (by) ms_view_rotate_by(&app->world, axis, deg);
    else ms_view_rotate_to(&app->world, axis, deg);
    return TCL_OK;
}

static int translate_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int by;
    float v[3];
    if (objc != 5) return ms_cmd_error(interp, "translate: usage: translate by|to <x> <y> <z>");
    if (get_by(interp, objv[1], "translate", &by)) return TCL_ERROR;
    for (int k = 0; k < 3; k++)
        if (ms_cmd_get_float(interp, objv[2 + k], &v[k], "translate")) return TCL_ERROR;
    ms_view_translate(&((ms_app *)cd)->world, v[0], v[1], v[2], by);
    return TCL_OK;
}

static int scale_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int by;
    float s;
    if (objc != 3) return ms_cmd_error(interp, "scale: usage: scale by|to <factor>");
    if (get_by(interp, objv[1], "scale", &by) || ms_cmd_get_float(interp, objv[2], &s, "scale"))
        return TCL_ERROR;
    if (ms_view_scale(&((ms_app *)cd)->world, s, by))
        return ms_cmd_error(interp, "scale: the factor must be positive, got %g", s);
    return TCL_OK;
}

static int rock_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_app *app = cd;
    if (objc == 2 && !strcasecmp(Tcl_GetString(objv[1]), "off")) {
        ms_view_rock(&app->world, '\0', 0, 0);
        return TCL_OK;
    }
    char axis;
    int by;
    float step;
    long steps = -1;
    if (objc != 4 && objc != 5)
        return ms_cmd_error(interp, "rock: usage: rock x|y|z by <increment> ?<steps>? | rock off");
    if (get_axis(interp, objv[1], "rock", &axis) || get_by(interp, objv[2], "rock", &by) ||
        ms_cmd_get_float(interp, objv[3], &step, "rock") ||
        (objc == 5 && ms_cmd_get_count(interp, objv[4], 0x7fffffffL, "rock steps", &steps)))
        return TCL_ERROR;
    if (!by) return ms_cmd_error(interp, "rock: expected 'by', got 'to'");
    ms_view_rock(&app->world, axis, step, (int)steps);
    return TCL_OK;
}

static int rotmat_cmd(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int by;
    float v[9], r[16];
    if (objc != 11) return ms_cmd_error(interp, "rotmat: usage: rotmat by|to <r11> <r12> ... <r33>");
    if (get_by(interp, objv[1], "rotmat", &by)) return TCL_ERROR;
    for (int i = 0; i < 9; i++)
        if (ms_cmd_get_float(interp, objv[2 + i], &v[i], "rotmat")) return TCL_ERROR;
    /* VMD fills its column-major matrix with the nine numbers in order, so the numbers
     * given as a row become a column. */
    ms_mat4_identity(r);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[4 * j + i] = v[3 * i + j];
    ms_view_rotmat(&((ms_app *)cd)->world, r, by);
    return TCL_OK;
}

void ms_cmd_trans_register(ms_app *app)
{
    Tcl_CreateObjCommand(app->interp, "rotate", rotate_cmd, app, NULL);
    Tcl_CreateObjCommand(app->interp, "translate", translate_cmd, app, NULL);
    Tcl_CreateObjCommand(app->interp, "scale", scale_cmd, app, NULL);
    Tcl_CreateObjCommand(app->interp, "rock", rock_cmd, app, NULL);
    Tcl_CreateObjCommand(app->interp, "rotmat", rotmat_cmd, app, NULL);
}
