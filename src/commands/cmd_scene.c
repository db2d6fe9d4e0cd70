/* cmd_scene.c: the argument parsers the scene-side commands (scenecmds.h) share. */
#include "config.h"
#include "commands/scenecmds.h"

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
