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
#include "base/base.h"
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
    int failed;                /* commands of scripts and standard input that failed */
    char first_failure[1024];   /* where the first one was, and its message */
    struct ms_ofile *log;      /* the command log (logfile <file>), or NULL */
    int log_console;           /* logfile console: the log goes to stdout */
    int con_loglevel;          /* vmdcon -loglevel: 0 all, 1 info, 2 warn, 3 err, 5 none */
    Tcl_Obj *user_keys;        /* user add key: a dict key -> command (NULL: none yet) */
    Tcl_Obj *menus;            /* menu states: a dict name -> {on x y} (NULL: defaults) */
    char spaceball_mode[16];   /* spaceball mode|sensitivity|nullregion, as set */
    double spaceball_sensitivity, spaceball_null;
} ms_app;

/* A set of Tcl commands to create on the application's interpreter (commands/commands.h
 * lists molscope's in ms_command_sets). */
typedef void (*ms_app_cmdset_fn)(ms_app *app);

/* Create the application: the molecule set, the plugins, the Tcl interpreter with VMD's
 * trace variables and update/vwait finishing pending loads, the world, then every command
 * set of the NULL-terminated table `commands` in order (NULL: none; quit and exit are one
 * of molscope's, commands/cmd_quit.c). NULL on failure (the reason is printed). */
ms_app *ms_app_new(const char *argv0, const ms_app_cmdset_fn *commands);
/* The same for a program said to be at exe_path (the Python module, whose process is
 * python3, names where a molscope program would be): the Tcl library and the plugins are
 * found from there. */
ms_app *ms_app_new_at(const char *exe_path, const char *argv0, const ms_app_cmdset_fn *commands);
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

/* Scripts read as VMD reads them (script.c). */
/* Run the file's commands one complete command at a time at the global level, echoing
 * results and printing errors (counted) and going on; stops at quit. TCL_ERROR when the
 * file cannot be opened, or when a command failed and ms_app_stop_on_error. */
int ms_app_play(ms_app *app, const char *path);
/* Log, evaluate one complete command at the global level, echo its result (rank 0) or
 * report its failure (ms_app_note_failure). A quit is TCL_OK. */
int ms_app_run_command(ms_app *app, Tcl_Obj *cmd, const char *where, int line);
/* Print the interpreter's error (the message on stdout as VMD does; where, line and the
 * stack trace on stderr) and count it. where may be NULL, line 0 when unknown. */
void ms_app_note_failure(ms_app *app, const char *where, int line);
/* Whether a failed command ends the run (several MPI ranks: the others would hang). */
int ms_app_stop_on_error(void);
/* The exit status of a batch run: status, or 1 when it is 0 and commands failed (then a
 * line on stderr says how many and which was first). Interactive runs keep status. */
int ms_app_exit_status(ms_app *app, int status);
/* The command log: open it on path (NULL: the console, stdout), replacing any log open;
 * close it (the file is put in place). 0, or -1 with err set. */
int ms_app_log_open(ms_app *app, const char *path, ms_error *err);
int ms_app_log_close(ms_app *app, ms_error *err);

#endif
