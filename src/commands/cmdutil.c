/* cmdutil.c: subcommand dispatch, molecule ids and molspecs, errors, and the shared file
 * loading used by `mol new`, `mol addfile` and `animate read`. */
#include "config.h"
#include "commands/commands.h"
#include "assemble/view.h"
#include "fileio/load.h"
#include "parallel/parallel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>


struct ms_cmdset {
    char *name;
    ms_app *app;
    ms_subcmd *items;
    unsigned char *quiet_items;   /* per item: never changes the picture */
    size_t n, cap;
    ms_subcmd_fn fallback;
    int quiet;              /* no subcommand changes the picture */
};

#define MS_MAX_CMDSETS 32
static ms_cmdset *cmdsets[MS_MAX_CMDSETS];
static int ncmdsets;

int ms_cmd_error(Tcl_Interp *interp, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    Tcl_Obj *msg = Tcl_NewObj();
    char buf[2048];
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    Tcl_AppendToObj(msg, buf, -1);
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

static ms_cmdset *find_set(const char *name)
{
    for (int i = 0; i < ncmdsets; i++)
        if (!strcmp(cmdsets[i]->name, name)) return cmdsets[i];
    return NULL;
}

static Tcl_Obj *subcommand_list(const ms_cmdset *s)
{
    Tcl_Obj *o = Tcl_NewObj();
    for (size_t i = 0; i < s->n; i++) {
        if (i) Tcl_AppendToObj(o, i + 1 == s->n ? ", or " : ", ", -1);
        Tcl_AppendToObj(o, s->items[i].name, -1);
    }
    return o;
}

static int cmdset_proc(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_cmdset *s = cd;
    if (objc < 2) {
        Tcl_Obj *msg = Tcl_ObjPrintf("%s: missing subcommand: must be ", s->name);
        Tcl_AppendObjToObj(msg, subcommand_list(s));
        Tcl_SetObjResult(interp, msg);
        return TCL_ERROR;
    }
    const char *word = Tcl_GetString(objv[1]);
    for (size_t i = 0; i < s->n; i++)
        if (ms_word_eq(word, s->items[i].name)) {
            if (!s->quiet && !s->quiet_items[i]) s->app->world.scene_version++;
            return s->items[i].fn(s->app, interp, objc, objv);
        }
    if (s->fallback) {
        if (!s->quiet) s->app->world.scene_version++;
        return s->fallback(s->app, interp, objc, objv);
    }
    Tcl_Obj *msg = Tcl_ObjPrintf("%s: unknown subcommand \"%s\": must be ", s->name, word);
    Tcl_AppendObjToObj(msg, subcommand_list(s));
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

static int extend(const char *name, const ms_subcmd *table, int quiet)
{
    ms_cmdset *s = find_set(name);
    if (!s) return -1;
    for (const ms_subcmd *t = table; t->name; t++) {
        size_t cap = s->cap;
        if (ms_grow((void **)&s->items, &s->cap, s->n + 1, sizeof *s->items)) return -1;
        if (s->cap != cap) {
            unsigned char *q = realloc(s->quiet_items, s->cap);
            if (!q) return -1;
            s->quiet_items = q;
        }
        s->quiet_items[s->n] = (unsigned char)quiet;
        s->items[s->n++] = *t;
    }
    return 0;
}

int ms_cmdset_extend(ms_app *app, const char *name, const ms_subcmd *table)
{
    return extend(name, table, 0);
}

int ms_cmdset_extend_quiet(ms_app *app, const char *name, const ms_subcmd *table)
{
    return extend(name, table, 1);
}

static void cmdset_delete(ClientData cd)
{
    ms_cmdset *s = cd;
    for (int i = 0; i < ncmdsets; i++)
        if (cmdsets[i] == s) {
            cmdsets[i] = cmdsets[--ncmdsets];
            break;
        }
    free(s->items);
    free(s->quiet_items);
    free(s->name);
    free(s);
}

ms_cmdset *ms_cmdset_create(ms_app *app, const char *name, const ms_subcmd *table)
{
    if (ncmdsets >= MS_MAX_CMDSETS) return NULL;
    ms_cmdset *s = calloc(1, sizeof *s);
    if (!s || !(s->name = ms_strdup(name))) {
        free(s);
        return NULL;
    }
    s->app = app;
    cmdsets[ncmdsets++] = s;
    if (table) ms_cmdset_extend(app, name, table);
    Tcl_CreateObjCommand(app->interp, name, cmdset_proc, s, cmdset_delete);
    return s;
}

void ms_cmdset_fallback(ms_app *app, const char *name, ms_subcmd_fn fn)
{
    ms_cmdset *s = find_set(name);
    if (s) s->fallback = fn;
}

void ms_cmdset_quiet(ms_app *app, const char *name)
{
    ms_cmdset *s = find_set(name);
    if (s) s->quiet = 1;
}

/* ---------------------------------------------------------------- molecules */

ms_molecule *ms_cmd_mol(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, const char *cmd)
{
    const char *w = Tcl_GetString(word);
    if (!strcasecmp(w, "top")) {
        ms_molecule *m = ms_molset_top(&app->mols);
        if (!m) ms_cmd_error(interp, "%s: no molecules are loaded (no top molecule)", cmd);
        return m;
    }
    int id;
    if (Tcl_GetIntFromObj(NULL, word, &id) != TCL_OK) {
        ms_cmd_error(interp, "%s: '%s' is not a molecule id", cmd, w);
        return NULL;
    }
    ms_molecule *m = ms_molset_get(&app->mols, id);
    if (!m) ms_cmd_error(interp, "%s: no molecule with id %d", cmd, id);
    return m;
}

/* Does molecule m match a molspec word? -1 when the word is not a molspec keyword. */
static int spec_match(const ms_molecule *m, const char *word, int top)
{
    if (!strcasecmp(word, "all")) return 1;
    if (!strcasecmp(word, "none")) return 0;
    if (!strcasecmp(word, "top")) return m->id == top;
    if (!strcasecmp(word, "active")) return m->active;
    if (!strcasecmp(word, "inactive")) return !m->active;
    if (!strcasecmp(word, "displayed") || !strcasecmp(word, "on")) return m->displayed;
    if (!strcasecmp(word, "off")) return !m->displayed;
    if (!strcasecmp(word, "fixed")) return m->fixed;
    if (!strcasecmp(word, "free") || !strcasecmp(word, "unfix")) return !m->fixed;
    return -1;
}

int ms_cmd_molspec(ms_app *app, Tcl_Interp *interp, const char *spec, const char *cmd,
                   int **out, int *n)
{
    size_t nm = app->mols.n;
    uint8_t *chosen = calloc(nm + 1, 1);
    char *copy = ms_strdup(spec);
    *out = calloc(nm + 1, sizeof **out);
    *n = 0;
    int rc = TCL_OK;
    if (!chosen || !copy || !*out) {
        rc = ms_cmd_error(interp, "%s: out of memory", cmd);
        goto done;
    }
    static const ms_molecule probe = {0};
    char *save = NULL;
    for (char *w = strtok_r(copy, "|/: \t", &save); w; w = strtok_r(NULL, "|/: \t", &save)) {
        char *end;
        long id = strtol(w, &end, 10);
        if (*end == '\0') {
            int i = ms_molset_index_of(&app->mols, (int)id);
            if (i < 0) {
                rc = ms_cmd_error(interp, "%s: no molecule with id %ld", cmd, id);
                goto done;
            }
            chosen[i] = 1;
        } else if (spec_match(&probe, w, -1) < 0) {
            rc = ms_cmd_error(interp, "%s: bad molecule specification '%s'", cmd, w);
            goto done;
        } else {
            for (size_t i = 0; i < nm; i++)
                if (spec_match(app->mols.mols[i], w, app->mols.top) > 0) chosen[i] = 1;
        }
    }
    for (size_t i = 0; i < nm; i++)
        if (chosen[i]) (*out)[(*n)++] = app->mols.mols[i]->id;
done:
    free(chosen);
    free(copy);
    if (rc != TCL_OK) {
        free(*out);
        *out = NULL;
        *n = 0;
    }
    return rc;
}

/* VMD's resetview on the top molecule: centre on the mean position of its atoms, scale so
 * the largest extent spans 1.5 units, no rotation or global translation; every molecule
 * gets the same view. The view module replaces this once representations exist. */
int ms_cmd_get_count(Tcl_Interp *interp, Tcl_Obj *obj, long max, const char *what, long *out)
{
    Tcl_WideInt v;
    if (Tcl_GetWideIntFromObj(NULL, obj, &v) != TCL_OK || v < 0 || v > max)
        return ms_cmd_error(interp, "%s: expected a whole number from 0 to %ld, got '%s'", what,
                            max, Tcl_GetString(obj));
    *out = (long)v;
    return TCL_OK;
}

/* ---------------------------------------------------------------- loading */

static int get_long_opt(Tcl_Interp *interp, const char *cmd, const char *opt, Tcl_Obj *v,
                        long lo, long *out)
{
    Tcl_WideInt w;
    if (Tcl_GetWideIntFromObj(NULL, v, &w) != TCL_OK || w < lo || w > 2147483647)
        return ms_cmd_error(interp, "%s: option %s: expected an integer >= %ld, got '%s'", cmd,
                            opt, lo, Tcl_GetString(v));
    *out = (long)w;
    return TCL_OK;
}

static int get_bool_opt(Tcl_Interp *interp, const char *cmd, const char *opt, Tcl_Obj *v,
                        int *out)
{
    if (Tcl_GetBooleanFromObj(NULL, v, out) != TCL_OK)
        return ms_cmd_error(interp, "%s: option %s: expected 0 or 1, got '%s'", cmd, opt,
                            Tcl_GetString(v));
    return TCL_OK;
}

int ms_cmd_parse_load_opts(Tcl_Interp *interp, const char *cmd, int objc, Tcl_Obj *const objv[],
                           int start, ms_load_opts *o, Tcl_Obj **molid_word)
{
    if (molid_word) *molid_word = NULL;
    for (int i = start; i < objc; i += 2) {
        const char *opt = Tcl_GetString(objv[i]);
        if (i + 1 >= objc) {
            if (molid_word) {
                *molid_word = objv[i];
                return TCL_OK;
            }
            return ms_cmd_error(interp, "%s: option '%s' has no value", cmd, opt);
        }
        Tcl_Obj *v = objv[i + 1];
        if (!strcasecmp(opt, "type")) {
            o->type = Tcl_GetString(v);
        } else if (!strcasecmp(opt, "first") || !strcasecmp(opt, "beg")) {
            if (get_long_opt(interp, cmd, opt, v, 0, &o->first)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "last") || !strcasecmp(opt, "end")) {
            if (get_long_opt(interp, cmd, opt, v, -1, &o->last)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "step") || !strcasecmp(opt, "skip")) {
            if (get_long_opt(interp, cmd, opt, v, 1, &o->step)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "waitfor")) {
            if (!strcasecmp(Tcl_GetString(v), "all")) o->waitfor = -1;
            else if (get_long_opt(interp, cmd, opt, v, -1, &o->waitfor)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "filebonds")) {
            if (get_bool_opt(interp, cmd, opt, v, &o->filebonds)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "autobonds")) {
            if (get_bool_opt(interp, cmd, opt, v, &o->autobonds)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "bcast")) {
            if (get_bool_opt(interp, cmd, opt, v, &o->bcast)) return TCL_ERROR;
        } else if (!strcasecmp(opt, "volsets")) {
            /* accepted: every data set of a volume file is read */
        } else if (!strcasecmp(opt, "assembly")) {
            o->assembly = Tcl_GetString(v);
        } else {
            return ms_cmd_error(interp,
                                "%s: unknown option '%s': must be type, first, last, step, "
                                "waitfor, filebonds, autobonds, volsets, assembly or bcast", cmd,
                                opt);
        }
    }
    if (o->last >= 0 && o->last < o->first)
        return ms_cmd_error(interp, "%s: last frame %ld comes before first frame %ld", cmd,
                            o->last, o->first);
    return TCL_OK;
}

/* `bcast on` with several ranks: a collective load (parallel.h). Never inside a `parallel
 * for` callback, where the other ranks are elsewhere and would never join. Returns 1 when
 * the load should be broadcast, 0 when not, -1 after setting an error. */
static int use_bcast(Tcl_Interp *interp, const char *cmd, const ms_load_opts *o)
{
    if (!o->bcast || !ms_par_bcast_enabled()) return 0;
    if (Tcl_GetAssocData(interp, "molscope::parallel::busy", NULL)) {
        ms_cmd_error(interp, "%s: bcast on cannot be used inside a parallel for callback: every "
                             "rank must load the file at the same point", cmd);
        return -1;
    }
    return 1;
}

int ms_cmd_load(ms_app *app, Tcl_Interp *interp, const char *cmd, const char *path,
                const ms_load_opts *o, ms_molecule *into)
{
    ms_error err = {{0}};
    int bcast = use_bcast(interp, cmd, o);
    if (bcast < 0) return TCL_ERROR;
    if (!into) {
        ms_molecule *m = bcast ? ms_par_load_new(&app->plugins, path, o, &err)
                               : ms_load_new(&app->plugins, path, o, &err);
        if (!m) return ms_cmd_error(interp, "%s: %s: %s", cmd, path, err.msg);
        if (ms_molset_add(&app->mols, m, &err)) {
            ms_mol_free(m);
            return ms_cmd_error(interp, "%s: %s: %s", cmd, path, err.msg);
        }
        if (m->nframes) ms_molset_set_frame(&app->mols, m, (long)m->nframes - 1);
        if (m->atoms.n) ms_molset_emit(&app->mols, MS_EV_STRUCTURE_LOADED, m, NULL);
        if (m->nvolumes) ms_molset_emit(&app->mols, MS_EV_VOLUMES, m, NULL);
        if (!m->atoms.n && m->nvolumes) ms_molset_emit(&app->mols, MS_EV_VOLUMES_LOADED, m, NULL);
        ms_view_reset(&app->world);
        if (m->pending) ms_app_schedule_loading(app);
        else ms_molset_emit(&app->mols, MS_EV_TRAJ_DONE, m, path);
        Tcl_SetObjResult(interp, Tcl_NewIntObj(m->id));
        return TCL_OK;
    }
    size_t atoms_before = into->atoms.n, frames_before = into->nframes;
    size_t volumes_before = into->nvolumes;
    if (bcast ? ms_par_load_add(&app->plugins, into, path, o, &err)
              : ms_load_add(&app->plugins, into, path, o, &err))
        return ms_cmd_error(interp, "%s: %s: %s", cmd, path, err.msg);
    if (atoms_before == 0 && into->atoms.n > 0) {
        ms_molset_emit(&app->mols, MS_EV_STRUCTURE, into, NULL);
        ms_molset_emit(&app->mols, MS_EV_STRUCTURE_LOADED, into, NULL);
        ms_view_reset(&app->world);
    }
    if (into->nvolumes != volumes_before) ms_molset_emit(&app->mols, MS_EV_VOLUMES, into, NULL);
    if (into->atoms.n == 0 && volumes_before == 0 && into->nvolumes) {
        ms_molset_emit(&app->mols, MS_EV_VOLUMES_LOADED, into, NULL);
        ms_view_reset(&app->world);
    }
    if (into->nframes != frames_before) {
        ms_molset_emit(&app->mols, MS_EV_FRAMES_ADDED, into, NULL);
        ms_molset_set_frame(&app->mols, into, (long)into->nframes - 1);
    }
    if (into->pending) ms_app_schedule_loading(app);
    else ms_molset_emit(&app->mols, MS_EV_TRAJ_DONE, into, path);
    Tcl_SetObjResult(interp, Tcl_NewIntObj(into->id));
    return TCL_OK;
}
