/* app.h: the running program's state: the Tcl interpreter, the molecules, the plugins, the
 * world they are shown in (assemble/world.h: colours, materials, view, reps, device
 * settings, display size), and the pieces of VMD's startup and shell behaviour. The Tcl
 * command bindings receive an ms_app* as their client data.
 *
 * Everything here is made by ms_app_new and freed by ms_app_free, nowhere else. */
#ifndef MS_APP_H
#define MS_APP_H

#include <tcl.h>

#include "assemble/world.h"
#include "fileio/registry.h"
#include "molecule/molset.h"

typedef struct ms_app {
    Tcl_Interp *interp;
    ms_molset mols;
    ms_registry plugins;
    ms_world world;            /* what the molecules are shown with, and the display size */
    char exe_path[4096];
    char tcllib_dir[4096];
    char dispdev[32];          /* as given: text, none, osmesa, egl, opengl, ... */
    int interactive;           /* stdin is a terminal */
    int quit_requested, quit_status;
    int idle_scheduled;        /* a background frame-loading callback is queued */
} ms_app;

/* A set of Tcl commands to create on the application's interpreter (commands/commands.h
 * lists molscope's in ms_command_sets). */
typedef void (*ms_app_cmdset_fn)(ms_app *app);

/* Create the application: the molecule set, the plugins, the Tcl interpreter with VMD's
 * trace variables and update/vwait finishing pending loads, the world, then every command
 * set of the NULL-terminated table `commands` in order (NULL: none; quit and exit are one
 * of molscope's, commands/cmd_quit.c). NULL on failure (the reason is printed). */
ms_app *ms_app_new(const char *argv0, const ms_app_cmdset_fn *commands);
/* Free everything ms_app_new made: the interpreter first (what lives on it, such as the live
 * view, stops with it), then the molecules, the world and the plugins. */
void ms_app_free(ms_app *app);

/* Source the Tcl library's init script. Returns TCL_OK or TCL_ERROR. */
int ms_app_source_init(ms_app *app);

/* Background frame loading (loading.c). Queue reading of pending frames (VMD's waitfor)
 * when Tcl is idle; cancel that queued reading (the loads stay pending). */
void ms_app_schedule_loading(ms_app *app);
void ms_app_stop_loading(ms_app *app);
/* Read every pending frame of every molecule now. A damaged file keeps the frames read
 * before the damage and is reported through the background error handler. */
void ms_app_finish_loading(ms_app *app);
/* The same for one molecule: 0, or -1 when a trace callback deleted it meanwhile. */
int ms_app_finish_molecule(ms_app *app, ms_molecule *m);
/* Make Tcl's update and vwait read every pending frame first. */
void ms_app_register_loading(ms_app *app);

/* Register the app's own commands (update/vwait; quit and exit are a command set of
 * commands/, cmd_quit.c) and the trace-variable listener. */
void ms_app_register(ms_app *app);

/* Evaluate a script as a top-level command (batch: an error prints the message and stack
 * trace). Returns TCL_OK, TCL_ERROR, or TCL_OK after a quit (check app->quit_requested). */
int ms_app_eval_file(ms_app *app, const char *path);

#endif
