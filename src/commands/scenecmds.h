/* scenecmds.h: the scene-side Tcl commands (color, colorinfo, material, display, axes,
 * stage, light, rotate, translate, scale, rock, rotmat, graphics, draw, render) and what
 * they share: small argument parsers. What they change is the application's world
 * (assemble/world.h). */
#ifndef MS_SCENECMDS_H
#define MS_SCENECMDS_H

#include "commands/commands.h"
#include "scene/graphics.h"

void ms_cmd_color_register(ms_app *app);
void ms_cmd_material_register(ms_app *app);
void ms_cmd_display_register(ms_app *app);
void ms_cmd_trans_register(ms_app *app);
void ms_cmd_graphics_register(ms_app *app);
/* display live (cmd_live.c): the live view in a browser (live/live.h). */
void ms_cmd_live_register(ms_app *app);
void ms_cmd_render_register(ms_app *app);

/* {x y z} into v; an error "<what>: expected {x y z}, got '...'" otherwise. */
int ms_cmd_get_vec3(Tcl_Interp *interp, Tcl_Obj *obj, float v[3], const char *what);
/* A finite number; an error "<what>: expected a number, got '...'" otherwise. */
int ms_cmd_get_float(Tcl_Interp *interp, Tcl_Obj *obj, float *out, const char *what);
/* A boolean (on/off, yes/no, 1/0, true/false). */
int ms_cmd_get_bool(Tcl_Interp *interp, Tcl_Obj *obj, int *out, const char *what);
/* VMD's "%f" text for a number, as its get commands return them. */
Tcl_Obj *ms_cmd_float_obj(double v);

#endif
