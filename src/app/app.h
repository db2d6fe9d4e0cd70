/* app.h: the running program: the Tcl interpreter, the molecules, the plugins, the display
 * settings from the command line, and the pieces of VMD's startup and shell behaviour. The
 * Tcl command bindings receive an ms_app* as their client data. */
#ifndef MS_APP_H
#define MS_APP_H

#include <tcl.h>

#include "fileio/registry.h"
#include "molecule/molset.h"

typedef struct ms_app {
    Tcl_Interp *interp;
    ms_molset mols;
    ms_registry plugins;
    char exe_path[4096];
    char tcllib_dir[4096];
    char dispdev[32];          /* as given: text, none, osmesa, egl, opengl, ... */
    int width, height;         /* display size in pixels (VMD's text mode: 512 x 512) */
    int interactive;           /* stdin is a terminal */
    int quit_requested, quit_status;
    int idle_scheduled;        /* a background frame-loading callback is queued */
    unsigned long scene_version;   /* bumped by whatever may change the picture: molecule
                                    * events, view changes, scene-changing commands (the
                                    * live view re-renders when it moves) */
    void *module[16];          /* state owned by other modules (scene, reps, ...) */
    /* Scene-side state, created by ms_cmd_scene_register (commands/scenecmds.h). */
    struct ms_colors *colors;        /* scene/color.h: colour table and categories */
    struct ms_materials *materials;  /* scene/material.h */
    struct ms_view *view;            /* view/view.h: camera, display settings, lights */
    struct ms_renderers *renderers;  /* render/render.h: per-device settings */
    int ugraphics_slot;              /* molecule attachment of user graphics, -1 if none */
    struct ms_rep_state *reps;       /* rep/rep.h: current rep settings, per-molecule reps */
} ms_app;

/* Create the application: interpreter, plugins, molecule set, commands. NULL on failure
 * (the reason is printed). */
ms_app *ms_app_new(const char *argv0);
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

/* Register the app's own commands (quit/exit, update/vwait) and the trace-variable
 * listener. */
void ms_app_register(ms_app *app);

/* Evaluate a script as a top-level command (batch: an error prints the message and stack
 * trace). Returns TCL_OK, TCL_ERROR, or TCL_OK after a quit (check app->quit_requested). */
int ms_app_eval_file(ms_app *app, const char *path);

#endif
