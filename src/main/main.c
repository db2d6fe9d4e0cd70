/* main.c: molscope's entry point. Starts MPI when a launcher started us (before anything
 * else, as VMD does), parses VMD's command line, starts the Tcl interpreter, and follows
 * VMD's startup order: the Tcl library's init script, the files named on the command line
 * (loaded by rank 0 and broadcast when there are several ranks), the first startup file
 * found, the -e script, then the shell. Scripts and standard input are read as VMD reads
 * them (app/script.c; a -python -e file is Python, python/): a failing command is reported and the next one runs; the exit status
 * is 1 when any failed. Every exit goes through ms_par_exit, so a non-zero status on any
 * rank ends the whole MPI job. */
#include "config.h"
#include "app/app.h"
#include "app/options.h"
#include "app/shell.h"
#include "assemble/view.h"
#include "commands/commands.h"
#include "gl/gl.h"
#include "parallel/parallel.h"
#ifdef MS_HAVE_PYTHON
#include "python/python.h"
#endif

#include <malloc.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static int is_plugin_type(void *ud, const char *name)
{
    return ms_registry_find(&((ms_app *)ud)->plugins, name) != NULL;
}

static void set_tcl_argv(ms_app *app, const char *argv0, const ms_options *o)
{
    Tcl_Obj *list = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < o->tcl_argc; i++)
        Tcl_ListObjAppendElement(NULL, list, Tcl_NewStringObj(o->tcl_argv[i], -1));
    Tcl_SetVar2Ex(app->interp, "argv", NULL, list, TCL_GLOBAL_ONLY);
    Tcl_SetVar2Ex(app->interp, "argc", NULL, Tcl_NewIntObj(o->tcl_argc), TCL_GLOBAL_ONLY);
    Tcl_SetVar2Ex(app->interp, "argv0", NULL, Tcl_NewStringObj(argv0, -1), TCL_GLOBAL_ONLY);
    Tcl_SetVar2Ex(app->interp, "tcl_interactive", NULL, Tcl_NewIntObj(app->interactive),
                  TCL_GLOBAL_ONLY);
}

/* Display devices: text and none need nothing (render snapshot opens an offscreen context
 * when it first draws); osmesa and egl start that back-end; opengl, openglpbuffer and win
 * (what VMD users type) start the best one available and say which. VMD's OpenGL displays
 * turn depth cueing on. A device that cannot start is reported with the reason and a device
 * that works, and text is used. */
static void choose_dispdev(ms_app *app, const char *dev)
{
    static const char *known[] = {"text", "none", "osmesa", "egl", "opengl", "openglpbuffer",
                                  "win", "cave", "caveforms", "freevr", "freevrforms"};
    int talk = ms_par_rank() == 0;  /* only rank 0 prints informational messages */
    if (!dev) return;
    size_t i = 0;
    while (i < sizeof known / sizeof known[0] && strcasecmp(dev, known[i]) != 0) i++;
    if (i == sizeof known / sizeof known[0]) {
        if (talk) fprintf(stderr, "molscope: unknown display device '%s'; using text\n", dev);
        return;
    }
    if (i >= 7) {
        if (talk) fprintf(stderr, "molscope: display device '%s' is not built into this version; using "
                        "text (render snapshot and the file renderers work without a display)\n", dev);
        return;
    }
    if (i < 2) {
        snprintf(app->dispdev, sizeof app->dispdev, "%s", known[i]);
        return;
    }
    char msg[1200];
    if (ms_gl_display_start(known[i], msg, sizeof msg) != 0) {
        if (talk) fprintf(stderr, "molscope: -dispdev %s: %s; using text\n", dev, msg);
        return;
    }
    ms_gl *g = ms_gl_display_current();
    snprintf(app->dispdev, sizeof app->dispdev, "%s", ms_gl_kind_name(ms_gl_kind_of(g)));
    if (i >= 4 && talk) fprintf(stderr, "molscope: -dispdev %s: using %s\n", dev, msg);
    app->world.view->settings.depthcue = 1;
}

/* After one startup stage: a quit ends the program with its status; a failure is counted
 * as a failed command and the startup goes on, as VMD's does (with several MPI ranks it ends
 * the program, ms_app_stop_on_error). Returns 0 to continue, or 1 to exit with *status. */
static int stage(ms_app *app, int rc, const char *what, int *status)
{
    if (app->quit_requested) {
        *status = app->quit_status;
        return 1;
    }
    if (rc == TCL_OK) return 0;
    ms_app_note_failure(app, what, 0);
    if (ms_app_stop_on_error()) {
        *status = 1;
        return 1;
    }
    return 0;
}

/* A script file (-e, the startup file), read as VMD reads it (app/script.c); with -python
 * the -e file is Python, run whole (a failure is one failed command). */
static int run_script(ms_app *app, const char *path, int python, int *status)
{
    int before = app->failed;
#ifdef MS_HAVE_PYTHON
    if (python) return stage(app, ms_python_run_file(app, path), path, status);
#endif
    int rc = ms_app_play(app, path);
    if (rc != TCL_OK && app->failed != before) {   /* a failure that stops the run */
        *status = 1;
        return 1;
    }
    return stage(app, rc, path, status);
}

static int load_cmdline_files(ms_app *app, const ms_options *o, int *status)
{
    for (int i = 0; i < o->nfiles; i++) {
        const ms_cmdfile *f = &o->files[i];
        Tcl_Obj *cmd = Tcl_NewListObj(0, NULL);
        Tcl_IncrRefCount(cmd);
        Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("mol", -1));
        Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj(f->new_molecule ? "new" : "addfile", -1));
        Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj(f->path, -1));
        if (f->type) {
            Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("type", -1));
            Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj(f->type, -1));
        }
        Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("waitfor", -1));
        Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("all", -1));
        /* Every rank reaches this point with the same command line: rank 0 reads. */
        if (ms_par_bcast_enabled()) {
            Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("bcast", -1));
            Tcl_ListObjAppendElement(NULL, cmd, Tcl_NewStringObj("on", -1));
        }
        int rc = Tcl_EvalObjEx(app->interp, cmd, TCL_EVAL_GLOBAL);
        Tcl_DecrRefCount(cmd);
        if (stage(app, rc, "command line", status)) return 1;
    }
    return 0;
}

static int run_startup_file(ms_app *app, const ms_options *o, int *status)
{
    char path[4096];
    const char *home = getenv("HOME");
    if (o->startup) {
        if (access(o->startup, R_OK) != 0) {
            Tcl_SetObjResult(app->interp, Tcl_ObjPrintf("-startup %s: cannot read the file",
                                                         o->startup));
            return stage(app, TCL_ERROR, "command line", status);
        }
        return run_script(app, o->startup, 0, status);
    }
    const char *names[] = {".molscoperc", ".vmdrc"};
    for (int k = 0; k < 2; k++) {
        const char *dirs[] = {".", home};
        for (int d = 0; d < 2; d++) {
            if (!dirs[d]) continue;
            snprintf(path, sizeof path, "%s/%s", dirs[d], names[k]);
            if (access(path, R_OK) == 0)
                return run_script(app, path, 0, status);
        }
    }
    return 0;
}

/* Tcl_Exit from anywhere (a package, Tcl_Panic's cousins) ends the job the same way. */
static void exit_proc(ClientData cd)
{
    int status = (int)(intptr_t)cd;
    fflush(stdout);
    exit(ms_par_exit(status));
}

int main(int argc, char **argv)
{
    ms_error perr = {{0}};
    if (ms_par_init(&argc, &argv, &perr) != 0) {
        fprintf(stderr, "molscope: cannot start MPI: %s\n", perr.msg);
        return 1;
    }
    /* A fixed mmap threshold keeps every large array in its own mapping, returned to the
     * system when freed: without it glibc raises the threshold after the first large free
     * and the big transient buffers of a load (bond pairs, grids) stay resident. */
    mallopt(M_MMAP_THRESHOLD, 256 * 1024);
    ms_app *app = ms_app_new(argv[0], ms_command_sets);
    if (!app) {
        fprintf(stderr, "molscope: cannot start (out of memory)\n");
        return ms_par_exit(1);
    }
    Tcl_SetExitProc(exit_proc);
#ifdef MS_HAVE_PYTHON
    ms_python_register(app);
#endif
    ms_options o;
    int status = 0;
    if (ms_options_parse(argc, argv, is_plugin_type, app, &o) != 0) {
        status = 2;
        goto done;
    }
    if (o.help || o.version) {
        if (ms_par_rank() == 0) {
            if (o.help) ms_options_usage(argv[0]);
            else printf("molscope %s\n", PACKAGE_VERSION);
        }
        goto done;
    }
    if (ms_par_rank() == 0 && ms_par_size() > 1)
        fprintf(stderr, "molscope: parallel: %d ranks\n", ms_par_size());
    ms_par_share_cores();
    app->interactive = isatty(0) && ms_par_size() == 1;
    choose_dispdev(app, o.dispdev);
    if (o.width) {
        app->world.width = o.width;
        app->world.height = o.height;
    }
    set_tcl_argv(app, argv[0], &o);

    if (ms_app_source_init(app) != TCL_OK) {
        ms_shell_report_error(app, "molscope: init.tcl");
        status = 1;
        goto done;
    }
    if (load_cmdline_files(app, &o, &status) || run_startup_file(app, &o, &status) ||
        (o.escript && run_script(app, o.escript, o.python, &status)))
        goto done;
    status = ms_shell_run(app);
done:
    status = ms_app_exit_status(app, status);
    ms_options_free(&o);
    Tcl_SetExitProc(NULL);
    ms_app_free(app);
    fflush(stdout);
    return ms_par_exit(status);
}
