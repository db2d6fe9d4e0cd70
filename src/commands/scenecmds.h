/* scenecmds.h: the scene-side Tcl commands (color, colorinfo, material, display, axes,
 * stage, light, rotate, translate, scale, rock, rotmat, graphics, draw, render) and what
 * they share: the state they create on the application and the form of numbers they
 * return. Arguments are read with the argument layer (args.h). */
#ifndef MS_SCENECMDS_H
#define MS_SCENECMDS_H

#include "commands/commands.h"
#include "scene/graphics.h"

/* Create the scene state (colours, materials, view, renderers, user-graphics slot), hook
 * it to molecule events and register every command below. */
void ms_cmd_scene_register(ms_app *app);

void ms_cmd_color_register(ms_app *app);
void ms_cmd_material_register(ms_app *app);
void ms_cmd_display_register(ms_app *app);
void ms_cmd_trans_register(ms_app *app);
void ms_cmd_graphics_register(ms_app *app);
/* display live (cmd_live.c): the live view in a browser (live/live.h). */
void ms_cmd_live_register(ms_app *app);
void ms_cmd_render_register(ms_app *app);

/* VMD's "%f" text for a number, as its get commands return them. */
Tcl_Obj *ms_cmd_float_obj(double v);

/* The user graphics of a molecule, created on first use; NULL when memory runs out. */
ms_ugraphics *ms_cmd_ugraphics(ms_app *app, ms_molecule *m);

#endif
