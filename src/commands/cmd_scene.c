/* cmd_scene.c: what the scene-side commands (scenecmds.h) share: the form of numbers they
 * return (their arguments are read with args.h). */
#include "config.h"
#include "commands/scenecmds.h"

#include <stdio.h>
#include <stdlib.h>

Tcl_Obj *ms_cmd_float_obj(double v)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%f", v);
    return Tcl_NewStringObj(buf, -1);
}
