/* scenecmds.h: the scene-side Tcl commands (color, colorinfo, material, display, axes,
 * stage, light, rotate, translate, scale, rock, rotmat, graphics, draw, render) and what
 * they share: the form of numbers they return. What they change is the application's world
 * (assemble/world.h). Arguments are read with the argument layer (args.h). */
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
/* label (cmd_label.c): VMD's labels (assemble/labels.h). */
void ms_cmd_label_register(ms_app *app);
/* save_state (cmd_state.c): the session as a VMD state script. */
void ms_cmd_state_register(ms_app *app);

/* VMD's "%f" text for a number, as its get commands return them. */
Tcl_Obj *ms_cmd_float_obj(double v);

#endif
