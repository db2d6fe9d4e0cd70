/* cmd_menu.c: VMD's `menu` command with no display. Plugins register their windows when
 * they load (`menu tk register` through vmd_install_extension, `menu tk add`) and scripts
 * open menus (`menu main on`); with no GUI nothing is drawn, but the menus and their state
 * are kept so these calls work and `status` answers as VMD does (doc/commands.md):
 *
 *   menu list                                   the names of the menus
 *   menu tk add <name> <window>                 a Tk window as a menu
 *   menu tk register <name> <proc> ?<path>?     a menu made by a proc, under a menu path
 *   menu tk remove <name>
 *   menu <name> on|off|status|loc|move <x> <y>  shown state and place (nothing is drawn) */
#include "config.h"
#include "commands/commands.h"

#include <limits.h>
#include <stdlib.h>

#define MENU_KEY "molscope::menus"

typedef struct menu_entry {
    int on, x, y, removable;
    Tcl_Obj *target, *path;    /* the window or proc, and the menu path (NULL: none) */
} menu_entry;

/* VMD's own menus, always there. */
static const char *const builtin_menus[] = {"main", "files", "graphics", "labels", "render",
                                            "display", "color", "tool", NULL};

static void entry_free(menu_entry *e)
{
    if (e->target) Tcl_DecrRefCount(e->target);
    if (e->path) Tcl_DecrRefCount(e->path);
    free(e);
}

static void menus_free(ClientData cd, Tcl_Interp *interp)
{
    (void)interp;
    Tcl_HashTable *t = cd;
    Tcl_HashSearch s;
    for (Tcl_HashEntry *h = Tcl_FirstHashEntry(t, &s); h; h = Tcl_NextHashEntry(&s))
        entry_free(Tcl_GetHashValue(h));
    Tcl_DeleteHashTable(t);
    free(t);
}

static Tcl_HashTable *menus(Tcl_Interp *interp)
{
    Tcl_HashTable *t = Tcl_GetAssocData(interp, MENU_KEY, NULL);
    if (t) return t;
    t = malloc(sizeof *t);
    if (!t) return NULL;
    Tcl_InitHashTable(t, TCL_STRING_KEYS);
    for (size_t i = 0; builtin_menus[i]; i++) {
        int isnew;
        Tcl_HashEntry *h = Tcl_CreateHashEntry(t, builtin_menus[i], &isnew);
        Tcl_SetHashValue(h, calloc(1, sizeof(menu_entry)));
    }
    Tcl_SetAssocData(interp, MENU_KEY, menus_free, t);
    return t;
}

static int menu_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc, (void)objv;
    Tcl_HashTable *t = menus(interp);
    if (!t) return ms_cmd_error(interp, "menu list: out of memory");
    Tcl_Obj *r = Tcl_NewListObj(0, NULL);
    Tcl_HashSearch s;
    for (Tcl_HashEntry *h = Tcl_FirstHashEntry(t, &s); h; h = Tcl_NextHashEntry(&s))
        Tcl_ListObjAppendElement(NULL, r, Tcl_NewStringObj(Tcl_GetHashKey(t, h), -1));
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

/* menu tk add|register: a new menu, or the same name again replacing the old one. */
static int tk_define(Tcl_Interp *interp, Tcl_Obj *name, Tcl_Obj *target, Tcl_Obj *path)
{
    Tcl_HashTable *t = menus(interp);
    menu_entry *e = calloc(1, sizeof *e);
    if (!t || !e) {
        free(e);
        return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    }
    int isnew;
    Tcl_HashEntry *h = Tcl_CreateHashEntry(t, Tcl_GetString(name), &isnew);
    if (!isnew) {
        menu_entry *old = Tcl_GetHashValue(h);
        if (!old->removable) {
            free(e);
            return ms_cmd_error(interp, "%s: \"%s\" is one of VMD's own menus", ms_args_where(),
                                Tcl_GetString(name));
        }
        entry_free(old);
    }
    e->removable = 1;
    e->target = target;
    Tcl_IncrRefCount(target);
    if (path) Tcl_IncrRefCount(e->path = path);
    Tcl_SetHashValue(h, e);
    return TCL_OK;
}

static int tk_add(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    return tk_define(interp, objv[3], objv[4], NULL);
}

static int tk_register(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app;
    return tk_define(interp, objv[3], objv[4], objc > 5 ? objv[5] : NULL);
}

static int tk_remove(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    Tcl_HashTable *t = menus(interp);
    Tcl_HashEntry *h = t ? Tcl_FindHashEntry(t, Tcl_GetString(objv[3])) : NULL;
    if (!h || !((menu_entry *)Tcl_GetHashValue(h))->removable)
        return ms_cmd_error(interp, "menu tk remove: no menu \"%s\" added by a plugin",
                            Tcl_GetString(objv[3]));
    entry_free(Tcl_GetHashValue(h));
    Tcl_DeleteHashEntry(h);
    return TCL_OK;
}

static int menu_tk(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd tk[] = {
        {"add", tk_add, 2, 2, "<name> <window>"},
        {"register", tk_register, 2, 3, "<name> <proc> ?<menupath>?"},
        {"remove", tk_remove, 1, 1, "<name>"},
        {NULL, NULL, 0, 0, NULL}};
    return ms_args_dispatch(app, interp, objc, objv, 2, tk, NULL, "menu tk");
}

/* ---------------------------------------------------------------- menu <name> ... */

static menu_entry *named(Tcl_Interp *interp, Tcl_Obj *name)
{
    Tcl_HashTable *t = menus(interp);
    Tcl_HashEntry *h = t ? Tcl_FindHashEntry(t, Tcl_GetString(name)) : NULL;
    if (!h) ms_cmd_error(interp, "menu: no menu named \"%s\"", Tcl_GetString(name));
    return h ? Tcl_GetHashValue(h) : NULL;
}

static int show(Tcl_Interp *interp, Tcl_Obj *const objv[], int on)
{
    menu_entry *e = named(interp, objv[1]);
    if (!e) return TCL_ERROR;
    e->on = on;
    return TCL_OK;
}

static int m_on(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    return show(interp, objv, 1);
}

static int m_off(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    return show(interp, objv, 0);
}

static int m_status(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    menu_entry *e = named(interp, objv[1]);
    if (!e) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewStringObj(e->on ? "on" : "off", -1));
    return TCL_OK;
}

static int m_loc(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    menu_entry *e = named(interp, objv[1]);
    if (!e) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_ObjPrintf("%d %d", e->x, e->y));
    return TCL_OK;
}

static int m_move(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)app, (void)objc;
    menu_entry *e = named(interp, objv[1]);
    int x, y;
    if (!e || ms_arg_int(interp, objv[3], "x", INT_MIN, INT_MAX, &x) ||
        ms_arg_int(interp, objv[4], "y", INT_MIN, INT_MAX, &y))
        return TCL_ERROR;
    e->x = x, e->y = y;
    return TCL_OK;
}

static int menu_named(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd ops[] = {
        {"on", m_on, 0, 0, ""},       {"off", m_off, 0, 0, ""},
        {"status", m_status, 0, 0, ""}, {"loc", m_loc, 0, 0, ""},
        {"move", m_move, 2, 2, "<x> <y>"}, {NULL, NULL, 0, 0, NULL}};
    if (!named(interp, objv[1])) return TCL_ERROR;
    char where[64];
    snprintf(where, sizeof where, "menu %.40s", Tcl_GetString(objv[1]));
    return ms_args_dispatch(app, interp, objc, objv, 2, ops, NULL, where);
}

static const ms_subcmd menu_table[] = {
    {"list", menu_list, 0, 0, ""},
    {"tk", menu_tk, 1, MS_ARGS_ANY, "add|register|remove ..."},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_menu_register(ms_app *app)
{
    static const ms_subcmd by_name = {"<name>", menu_named, 1, 4,
                                      "<name> on|off|status|loc|move <x> <y>"};
    ms_cmdset_create(app, "menu", menu_table);
    ms_cmdset_fallback(app, "menu", &by_name);
    ms_cmdset_quiet(app, "menu");
}
