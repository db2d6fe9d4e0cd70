/* app.c: creating and freeing the application (everything it holds is made and freed here),
 * locating its Tcl library and plugins, and VMD's trace variables (background frame loading
 * is in loading.c; quit and exit are commands/cmd_quit.c's). */
#include "config.h"
#include "app/app.h"
#include "fileio/load.h"
#include "gl/gl.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int dir_has(const char *dir, const char *file)
{
    char path[PATH_MAX];
    struct stat sb;
    return snprintf(path, sizeof path, "%s/%s", dir, file) < (int)sizeof path &&
           stat(path, &sb) == 0;
}

/* The Tcl library: MOLSCOPE_TCLLIB, then <prefix>/share/molscope/tcl beside the program,
 * then the source tree when run from the build tree, then the configured directory. */
static void find_tcllib(ms_app *app)
{
    const char *env = getenv("MOLSCOPE_TCLLIB");
    char exe_dir[PATH_MAX], cand[PATH_MAX + 64];
    snprintf(exe_dir, sizeof exe_dir, "%s", app->exe_path);
    char *slash = strrchr(exe_dir, '/');
    if (slash) *slash = '\0';
    const char *rel[] = {"../share/molscope/tcl", "../tcl"};
    if (env && *env && dir_has(env, "init.tcl")) {
        snprintf(app->tcllib_dir, sizeof app->tcllib_dir, "%s", env);
        return;
    }
    for (size_t i = 0; i < sizeof rel / sizeof rel[0]; i++) {
        char real[PATH_MAX];
        snprintf(cand, sizeof cand, "%s/%s", exe_dir, rel[i]);
        if (dir_has(cand, "init.tcl") && realpath(cand, real)) {
            snprintf(app->tcllib_dir, sizeof app->tcllib_dir, "%s", real);
            return;
        }
    }
    snprintf(app->tcllib_dir, sizeof app->tcllib_dir, "%s", MS_TCLLIBDIR);
}

static void find_plugins(ms_app *app)
{
    ms_registry_load_default(&app->plugins, app->exe_path);
    /* Run from the build tree: plugins/.libs beside src/. */
    char dir[PATH_MAX], real[PATH_MAX];
    snprintf(dir, sizeof dir, "%s", app->exe_path);
    char *slash = strrchr(dir, '/');
    if (slash) {
        *slash = '\0';
        char cand[PATH_MAX + 32];
        snprintf(cand, sizeof cand, "%s/../plugins/.libs", dir);
        if (realpath(cand, real)) ms_registry_load_dir(&app->plugins, real);
    }
}

ms_app *ms_app_new(const char *argv0, const ms_app_cmdset_fn *commands)
{
    char exe[sizeof ((ms_app *)0)->exe_path];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) exe[n] = '\0';
    else snprintf(exe, sizeof exe, "%s", argv0);
    return ms_app_new_at(exe, argv0, commands);
}

ms_app *ms_app_new_at(const char *exe_path, const char *argv0, const ms_app_cmdset_fn *commands)
{
    ms_app *app = calloc(1, sizeof *app);
    if (!app) return NULL;
    snprintf(app->exe_path, sizeof app->exe_path, "%s", exe_path);
    strcpy(app->dispdev, "text");
    strcpy(app->spaceball_mode, "normal");   /* VMD's Spaceball defaults */
    app->spaceball_sensitivity = 1.0;
    app->spaceball_null = 16;
    ms_molset_init(&app->mols);
    ms_registry_init(&app->plugins);
    find_tcllib(app);
    find_plugins(app);

    Tcl_FindExecutable(argv0);
    app->interp = Tcl_CreateInterp();
    if (Tcl_Init(app->interp) != TCL_OK) {
        fprintf(stderr, "molscope: Tcl_Init: %s\n", Tcl_GetStringResult(app->interp));
        /* Tcl works without its own script library, with fewer conveniences. */
    }
    Tcl_SetVar2(app->interp, "env", "MOLSCOPE_TCLLIB", app->tcllib_dir, TCL_GLOBAL_ONLY);
    /* VMD's install folder, which scripts read: molscope's library (its tachyon_LINUXAMD64
     * runs the system's tachyon), unless the environment names one */
    if (!getenv("VMDDIR")) Tcl_SetVar2(app->interp, "env", "VMDDIR", app->tcllib_dir, TCL_GLOBAL_ONLY);
    ms_app_register(app);      /* first: the trace variables are set before others hear */
    ms_error err = {{0}};
    if (ms_world_init(&app->world, &app->mols, &err)) {
        fprintf(stderr, "molscope: cannot create the scene state: %s\n", err.msg);
        ms_app_free(app);
        return NULL;
    }
    for (size_t i = 0; commands && commands[i]; i++) commands[i](app);
    return app;
}

void ms_app_free(ms_app *app)
{
    if (!app) return;
    ms_app_stop_loading(app);
    for (size_t i = 0; i < app->mols.n; i++) ms_loader_cancel(app->mols.mols[i]);
    ms_error err = {{0}};
    if (ms_app_log_close(app, &err)) fprintf(stderr, "molscope: logfile: %s\n", err.msg);
    if (app->user_keys) Tcl_DecrRefCount(app->user_keys);
    if (app->menus) Tcl_DecrRefCount(app->menus);
    if (app->interp) {
        Tcl_SetVar(app->interp, "vmd_quit", "1", TCL_GLOBAL_ONLY);
        /* Whatever lives on the interpreter ends with it (the live view stops there),
         * before the molecules and the display lists it may hold go. */
        Tcl_DeleteInterp(app->interp);
    }
    ms_molset_free(&app->mols);
    ms_world_free(&app->world);
    ms_registry_free(&app->plugins);
    ms_gl_display_close();
    free(app);
}

int ms_app_source_init(ms_app *app)
{
    char path[PATH_MAX + 16];
    snprintf(path, sizeof path, "%s/init.tcl", app->tcllib_dir);
    if (access(path, R_OK) != 0) {
        Tcl_SetObjResult(app->interp,
                         Tcl_ObjPrintf("molscope: Tcl library not found (looked for %s; set "
                                       "MOLSCOPE_TCLLIB to its directory)", path));
        return TCL_ERROR;
    }
    return Tcl_EvalFile(app->interp, path);
}

/* ---------------------------------------------------------------- trace variables */

static void set_trace_var(ms_app *app, const char *var, int molid, const char *value)
{
    char key[32];
    snprintf(key, sizeof key, "%d", molid);
    Tcl_Obj *v = Tcl_NewStringObj(value, -1);
    Tcl_IncrRefCount(v);
    /* A trace callback that fails must not abort the command that changed the frame. */
    if (!Tcl_SetVar2Ex(app->interp, var, key, v, TCL_GLOBAL_ONLY))
        Tcl_BackgroundException(app->interp, TCL_ERROR);
    Tcl_DecrRefCount(v);
}

static void on_mol_event(void *ud, ms_mol_event ev, ms_molecule *m, const char *arg)
{
    ms_app *app = ud;
    char buf[32];
    app->world.scene_version++;
    switch (ev) {
    case MS_EV_MOL_NEW:
        set_trace_var(app, "vmd_initialize_structure", m->id, "1");
        break;
    case MS_EV_MOL_DELETE:
        ms_loader_cancel(m);
        set_trace_var(app, "vmd_initialize_structure", m->id, "0");
        break;
    case MS_EV_FRAME:
        snprintf(buf, sizeof buf, "%d", m->frame);
        set_trace_var(app, "vmd_frame", m->id, buf);
        break;
    case MS_EV_FRAMES_ADDED:
        snprintf(buf, sizeof buf, "%zu", m->nframes);
        set_trace_var(app, "vmd_timestep", m->id, buf);
        break;
    case MS_EV_TRAJ_DONE:
        set_trace_var(app, "vmd_trajectory_read", m->id, arg ? arg : "");
        break;
    default:
        break;
    }
}

void ms_app_register(ms_app *app)
{
    ms_app_register_loading(app);
    ms_molset_listen(&app->mols, on_mol_event, app);
}
