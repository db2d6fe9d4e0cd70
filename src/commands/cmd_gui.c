/* cmd_gui.c: VMD's commands for its graphical interface, as VMD answers them with no display,
 * so that scripts written for the desktop run in batch without an error:
 *
 *   menu list                         the menus' names
 *   menu <name> on|off|status|loc     show or hide (kept), "on"/"off", the position {x y}
 *   menu <name> move <x> <y>          the position (kept)
 *   menu tk add|register <name> ...   add an extension's menu; menu tk remove <name>
 *   mouse mode <mode> ?<submode>?     sets vmd_mouse_mode and vmd_mouse_submode
 *   mouse callback|rocking on|off;  mouse stoprotation
 *   tool create|change|scale|scaleforce|scalespring|offset|delete|rep|adddevice|
 *        removedevice|callback ...    accepted: there are no tracking devices
 *   user add key <key> <command>      a keyboard shortcut, kept (there is no keyboard)
 *   user add menu|subitem ...         accepted
 *   user list keys                    {key command} pairs, in the order added
 *   user print keys                   the same, printed
 *   spaceball mode ?normal|maxaxis|scale|animate|tracker|user?;  spaceball sensitivity ?<s>?;
 *   spaceball nullregion ?<n>?        the Spaceball's settings, checked and kept (there is no
 *                                     Spaceball to move the scene); without a value, the
 *                                     value kept (molscope's)
 *   help ?<topic>?                    VMD opens its documentation in a web browser; with no
 *                                     display molscope prints where its command reference
 *                                     is (and VMD's user guide's address) and returns that file
 *   tkcon ..., videostream ...        errors saying why: the Tk console and the video
 *                                     stream need VMD's window, which molscope never opens */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define VMD_GUIDE_URL "https://www.ks.uiuc.edu/Research/vmd/current/ug/"

/* The menus VMD's interface has, all hidden at the start. */
static const char *const builtin_menus[] = {"main", "files", "graphics", "labels", "render",
                                            "display", "color", "material", "tool", NULL};

/* ---------------------------------------------------------------- menu */

/* The dict kept in *slot, made when there is none, unshared so that it can be changed. */
static Tcl_Obj *own_dict(Tcl_Obj **slot)
{
    if (!*slot) {
        *slot = Tcl_NewDictObj();
        Tcl_IncrRefCount(*slot);
    } else if (Tcl_IsShared(*slot)) {
        Tcl_Obj *copy = Tcl_DuplicateObj(*slot);
        Tcl_IncrRefCount(copy);
        Tcl_DecrRefCount(*slot);
        *slot = copy;
    }
    return *slot;
}

static Tcl_Obj *menus(ms_app *app)
{
    if (!app->menus)
        for (int i = 0; builtin_menus[i]; i++)
            Tcl_DictObjPut(NULL, own_dict(&app->menus), Tcl_NewStringObj(builtin_menus[i], -1),
                           Tcl_NewStringObj("off 0 0", -1));
    return own_dict(&app->menus);
}

/* A menu's state {on|off x y}; a menu not seen before is added (extension menus). */
static Tcl_Obj *menu_state(ms_app *app, Tcl_Obj *name)
{
    Tcl_Obj *st = NULL;
    Tcl_DictObjGet(NULL, menus(app), name, &st);
    if (!st) {
        st = Tcl_NewStringObj("off 0 0", -1);
        Tcl_DictObjPut(NULL, menus(app), name, st);
    }
    return st;
}

static void menu_set(ms_app *app, Tcl_Obj *name, int at, Tcl_Obj *const v[], int n)
{
    Tcl_Obj *st = Tcl_DuplicateObj(menu_state(app, name));
    Tcl_ListObjReplace(NULL, st, at, n, n, v);
    Tcl_DictObjPut(NULL, menus(app), name, st);
}

static int menu_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc, (void)objv;
    Tcl_Obj *names = Tcl_NewListObj(0, NULL);
    Tcl_DictSearch s;
    Tcl_Obj *k, *v;
    int done;
    for (Tcl_DictObjFirst(NULL, menus(app), &s, &k, &v, &done); !done;
         Tcl_DictObjNext(&s, &k, &v, &done))
        Tcl_ListObjAppendElement(NULL, names, k);
    Tcl_DictObjDone(&s);
    Tcl_SetObjResult(interp, names);
    return TCL_OK;
}

static int menu_tk(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const ops[] = {"add", "register", "remove", NULL};
    int op;
    if (objc < 4) return ms_args_usage(interp);
    if (ms_arg_choice(interp, objv[2], ops, "menu tk operation", &op)) return TCL_ERROR;
    if (op == 2) Tcl_DictObjRemove(NULL, menus(app), objv[3]);
    else menu_state(app, objv[3]);
    return TCL_OK;
}

/* menu <name> on|off|status|loc|move ... */
static int menu_named(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const ops[] = {"on", "off", "status", "loc", "move", NULL};
    int op;
    if (ms_arg_choice(interp, objv[2], ops, "menu operation", &op)) return TCL_ERROR;
    if ((op == 4) != (objc == 5) || (op != 4 && objc != 3)) return ms_args_usage(interp);
    Tcl_Obj *st = menu_state(app, objv[1]);
    if (op <= 1) {
        Tcl_Obj *w = Tcl_NewStringObj(op == 0 ? "on" : "off", -1);
        menu_set(app, objv[1], 0, &w, 1);
    } else if (op == 4) {
        int x, y;
        if (ms_arg_int(interp, objv[3], "x", -100000, 100000, &x) ||
            ms_arg_int(interp, objv[4], "y", -100000, 100000, &y))
            return TCL_ERROR;
        menu_set(app, objv[1], 1, objv + 3, 2);
    } else {
        Tcl_Obj **v;
        int n;
        Tcl_ListObjGetElements(NULL, st, &n, &v);
        Tcl_SetObjResult(interp, op == 2 ? v[0] : Tcl_NewListObj(2, v + 1));
    }
    return TCL_OK;
}

/* ---------------------------------------------------------------- mouse and tool */

static int mouse_mode(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app;
    Tcl_SetVar2Ex(interp, "vmd_mouse_mode", NULL, objv[2], TCL_GLOBAL_ONLY);
    Tcl_SetVar2Ex(interp, "vmd_mouse_submode", NULL, objc > 3 ? objv[3] : Tcl_NewIntObj(-1),
                  TCL_GLOBAL_ONLY);
    return TCL_OK;
}

static int mouse_flag(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    int on;
    return ms_arg_bool(interp, objv[2], "on|off", &on);
}

/* Accepted and answered with nothing: with no display there is nothing to change. */
static int accept(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)interp, (void)objc, (void)objv;
    return TCL_OK;
}

/* ---------------------------------------------------------------- spaceball */

static int spaceball_mode(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const modes[] = {"normal", "maxaxis", "scale", "animate", "tracker",
                                        "user", NULL};
    int k;
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(app->spaceball_mode, -1));
        return TCL_OK;
    }
    if (ms_arg_choice(interp, objv[2], modes, "spaceball mode", &k)) return TCL_ERROR;
    snprintf(app->spaceball_mode, sizeof app->spaceball_mode, "%s", modes[k]);
    return TCL_OK;
}

static int spaceball_value(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    double v;
    int sens = ms_word_eq(Tcl_GetString(objv[1]), "sensitivity");
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewDoubleObj(sens ? app->spaceball_sensitivity
                                                       : app->spaceball_null));
        return TCL_OK;
    }
    if (ms_arg_double_range(interp, objv[2], sens ? "sensitivity" : "null region", 0,
                            sens ? 1e6 : 1e9, &v))
        return TCL_ERROR;
    if (sens) app->spaceball_sensitivity = v;
    else app->spaceball_null = v;
    return TCL_OK;
}

/* ---------------------------------------------------------------- help, tkcon, videostream */

/* molscope's command reference: installed beside the program, in the source tree of a
 * build, or in the configured documentation folder; NULL when none is there. */
static const char *commands_doc(const ms_app *app, char *buf, size_t size)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", app->exe_path);
    char *slash = strrchr(dir, '/');
    if (slash) *slash = '\0';
    const char *rel[] = {"%s/../share/doc/molscope/commands.md", "%s/../doc/commands.md"};
    char cand[4200];
    for (size_t i = 0; i < MS_COUNTOF(rel); i++) {
        snprintf(cand, sizeof cand, rel[i], slash ? dir : ".");
        if (access(cand, R_OK) == 0 && size >= PATH_MAX && realpath(cand, buf)) return buf;
    }
    snprintf(buf, size, "%s/commands.md", MS_DOCDIR);
    return access(buf, R_OK) == 0 ? buf : NULL;
}

static int cmd_help(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    char buf[4200];
    const char *doc = commands_doc(app, buf, sizeof buf);
    printf("Info) help: there is no web browser without a display; molscope's command "
           "reference is %s", doc ? doc : "doc/commands.md of its sources (not installed)");
    if (objc > 1) printf(" (look for %s there)", Tcl_GetString(objv[1]));
    printf("\nInfo) VMD's user guide: %s\n", VMD_GUIDE_URL);
    fflush(stdout);
    Tcl_SetObjResult(interp, Tcl_NewStringObj(doc ? doc : VMD_GUIDE_URL, -1));
    return TCL_OK;
}

static int no_window(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    int tk = ms_word_eq(Tcl_GetString(objv[0]), "tkcon");
    return ms_cmd_error(interp, "%s: %s needs VMD's graphical window, and molscope runs "
                        "without one (as vmd -dispdev text)%s", Tcl_GetString(objv[0]),
                        tk ? "the Tk console" : "remote video streaming",
                        tk ? ": commands are read from standard input" :
                             ": make frames or videos with render and movie make, or watch "
                             "the scene with display live");
}

/* ---------------------------------------------------------------- user */

static Tcl_Obj *user_keys(ms_app *app)
{
    return own_dict(&app->user_keys);
}

static int user_add(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const what[] = {"key", "menu", "subitem", NULL};
    int w;
    if (ms_arg_choice(interp, objv[2], what, "user add", &w)) return TCL_ERROR;
    if (w != 0) return TCL_OK;
    if (objc != 5) return ms_cmd_error(interp, "user add key: wrong # args: usage: user add key "
                                               "<key> <command>");
    Tcl_DictObjPut(NULL, user_keys(app), objv[3], objv[4]);
    return TCL_OK;
}

static int user_keys_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    static const char *const what[] = {"keys", NULL};
    int w, print = ms_word_eq(Tcl_GetString(objv[1]), "print");
    if (ms_arg_choice(interp, objv[2], what, NULL, &w)) return TCL_ERROR;
    Tcl_Obj *pairs = Tcl_NewListObj(0, NULL);
    Tcl_DictSearch s;
    Tcl_Obj *k, *v;
    int done;
    if (print) printf("Keyboard shortcuts:\n-------------------\n");
    for (Tcl_DictObjFirst(NULL, user_keys(app), &s, &k, &v, &done); !done;
         Tcl_DictObjNext(&s, &k, &v, &done)) {
        Tcl_Obj *pair[2] = {k, v};
        Tcl_ListObjAppendElement(NULL, pairs, Tcl_NewListObj(2, pair));
        if (print) printf("'%s' : %s\n", Tcl_GetString(k), Tcl_GetString(v));
    }
    Tcl_DictObjDone(&s);
    if (!print) {
        Tcl_SetObjResult(interp, pairs);
        return TCL_OK;
    }
    fflush(stdout);
    Tcl_IncrRefCount(pairs);
    Tcl_DecrRefCount(pairs);
    return TCL_OK;
}

void ms_cmd_gui_register(ms_app *app)
{
    static const ms_subcmd menu_table[] = {{"list", menu_list, 0, 0, ""},
                                           {"tk", menu_tk, 2, MS_ARGS_ANY, "add|register|remove <name> ..."},
                                           {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd menu_fallback = {"<name>", menu_named, 2, 4,
                                              "<name> on|off|status|loc|move <x> <y>"};
    static const ms_subcmd mouse_table[] = {{"mode", mouse_mode, 1, 2, "<mode> ?<submode>?"},
                                            {"callback", mouse_flag, 1, 1, "on|off"},
                                            {"rocking", mouse_flag, 1, 1, "on|off"},
                                            {"stoprotation", accept, 0, 0, ""},
                                            {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd tool_table[] = {
        {"create", accept, 1, MS_ARGS_ANY, "<type> ?<device> ...?"},
        {"change", accept, 1, 2, "<type> ?<toolid>?"},
        {"scale", accept, 1, 2, "<scale> ?<toolid>?"},
        {"scaleforce", accept, 1, 2, "<scale> ?<toolid>?"},
        {"scalespring", accept, 1, 2, "<scale> ?<toolid>?"},
        {"offset", accept, 1, 2, "<offset> ?<toolid>?"},
        {"delete", accept, 0, 1, "?<toolid>?"},
        {"rep", accept, 1, 3, "<toolid> ?<molid> <repid>?"},
        {"adddevice", accept, 1, 2, "<device> ?<toolid>?"},
        {"removedevice", accept, 1, 2, "<device> ?<toolid>?"},
        {"callback", mouse_flag, 1, 1, "on|off"},
        {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd user_table[] = {{"add", user_add, 1, MS_ARGS_ANY, "key <key> <command> | menu ... | subitem ..."},
                                           {"list", user_keys_cmd, 1, 1, "keys"},
                                           {"print", user_keys_cmd, 1, 1, "keys"},
                                           {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd spaceball_table[] = {
        {"mode", spaceball_mode, 0, 1, "?normal|maxaxis|scale|animate|tracker|user?"},
        {"sensitivity", spaceball_value, 0, 1, "?<value>?"},
        {"nullregion", spaceball_value, 0, 1, "?<value>?"},
        {NULL, NULL, 0, 0, NULL}};
    static const ms_subcmd singles[] = {{"help", cmd_help, 0, 1, "?<topic>?"},
                                        {"tkcon", no_window, 0, MS_ARGS_ANY, "?<args>?"},
                                        {"videostream", no_window, 0, MS_ARGS_ANY, "?<args>?"}};
    for (size_t i = 0; i < MS_COUNTOF(singles); i++) ms_cmd_create(app, &singles[i]);
    ms_cmdset_create(app, "spaceball", spaceball_table);
    ms_cmdset_create(app, "menu", menu_table);
    ms_cmdset_fallback(app, "menu", &menu_fallback);
    ms_cmdset_create(app, "mouse", mouse_table);
    ms_cmdset_create(app, "tool", tool_table);
    ms_cmdset_create(app, "user", user_table);
    ms_cmdset_quiet(app, "menu");
    ms_cmdset_quiet(app, "mouse");
    ms_cmdset_quiet(app, "tool");
    ms_cmdset_quiet(app, "user");
}
