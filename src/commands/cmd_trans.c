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
#include "vecmath/vecf.h"

/* x, y or z ("axis") into 'x', 'y' or 'z'. */
static int get_axis(Tcl_Interp *interp, Tcl_Obj *o, char *axis)
{
    static const char *const axes[] = {"x", "y", "z", NULL};
    int k;
    if (ms_arg_choice(interp, o, axes, "axis", &k)) return TCL_ERROR;
    *axis = "xyz"[k];
    return TCL_OK;
}

/* "by" -> 1, "to" -> 0, else an error. */
static int get_by(Tcl_Interp *interp, Tcl_Obj *o, int *by)
{
    static const char *const words[] = {"by", "to", NULL};
    int k;
    if (ms_arg_choice(interp, o, words, NULL, &k)) return TCL_ERROR;
    *by = k == 0;
    return TCL_OK;
}

static int rotate_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 2 && ms_word_eq(Tcl_GetString(objv[1]), "stop")) {
        ms_view_rock(&app->world, '\0', 0, 0);
        return TCL_OK;
    }
    if (objc < 4) return ms_args_usage(interp);
    char axis;
    int by;
    float deg, incr;
    if (get_axis(interp, objv[1], &axis) || get_by(interp, objv[2], &by) ||
        ms_arg_float(interp, objv[3], "angle", &deg) ||
        (objc == 5 && ms_arg_float(interp, objv[4], "increment", &incr)))
        return TCL_ERROR;
    if (by) ms_view_rotate_by(&app->world, axis, deg);
    else ms_view_rotate_to(&app->world, axis, deg);
    return TCL_OK;
}

static int translate_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int by;
    float v[3];
    if (get_by(interp, objv[1], &by)) return TCL_ERROR;
    for (int k = 0; k < 3; k++)
        if (ms_arg_float(interp, objv[2 + k], NULL, &v[k])) return TCL_ERROR;
    ms_view_translate(&app->world, v[0], v[1], v[2], by);
    return TCL_OK;
}

static int scale_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int by;
    float s;
    if (get_by(interp, objv[1], &by) || ms_arg_float(interp, objv[2], "factor", &s))
        return TCL_ERROR;
    if (ms_view_scale(&app->world, s, by))
        return ms_cmd_error(interp, "scale: the factor must be positive, got %g", s);
    return TCL_OK;
}

static int rock_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const by_word[] = {"by", NULL};
    if (objc == 2 && ms_word_eq(Tcl_GetString(objv[1]), "off")) {
        ms_view_rock(&app->world, '\0', 0, 0);
        return TCL_OK;
    }
    if (objc < 4) return ms_args_usage(interp);
    char axis;
    int by;
    float step;
    long steps = -1;
    if (get_axis(interp, objv[1], &axis) || ms_arg_choice(interp, objv[2], by_word, NULL, &by) ||
        ms_arg_float(interp, objv[3], "increment", &step) ||
        (objc == 5 && ms_arg_long(interp, objv[4], "steps", 0, 0x7fffffffL, &steps)))
        return TCL_ERROR;
    ms_view_rock(&app->world, axis, step, (int)steps);
    return TCL_OK;
}

static int rotmat_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int by;
    float v[9], r[16];
    if (get_by(interp, objv[1], &by)) return TCL_ERROR;
    for (int i = 0; i < 9; i++)
        if (ms_arg_float(interp, objv[2 + i], NULL, &v[i])) return TCL_ERROR;
    /* VMD fills its column-major matrix with the nine numbers in order, so the numbers
     * given as a row become a column. */
    ms_mat4_identity(r);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[4 * j + i] = v[3 * i + j];
    ms_view_rotmat(&app->world, r, by);
    return TCL_OK;
}

void ms_cmd_trans_register(ms_app *app)
{
    static const ms_subcmd cmds[] = {
        {"rotate", rotate_cmd, 1, 4, "x|y|z by|to <angle> ?<increment>? | stop"},
        {"translate", translate_cmd, 4, 4, "by|to <x> <y> <z>"},
        {"scale", scale_cmd, 2, 2, "by|to <factor>"},
        {"rock", rock_cmd, 1, 4, "x|y|z by <increment> ?<steps>? | off"},
        {"rotmat", rotmat_cmd, 10, 10, "by|to <r11> <r12> <r13> <r21> <r22> <r23> <r31> <r32> <r33>"}};
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
