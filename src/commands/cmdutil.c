/* cmdutil.c: commands made of subcommand tables (on the argument layer, args.c), molecule
 * ids and molspecs, and the shared file loading used by `mol new`, `mol addfile` and
 * `animate read`. */
#include "config.h"
#include "commands/commands.h"
#include "assemble/view.h"
#include "fileio/load.h"
#include "parallel/parallel.h"

#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


struct ms_cmdset {
    char *name;
    ms_app *app;
    ms_subcmd *items;             /* n entries, then one with a NULL name */
    unsigned char *quiet_items;   /* per item: never changes the picture */
    size_t n, cap;
    ms_subcmd fallback;           /* fn NULL: none */
    int quiet;                    /* no subcommand changes the picture */
};

#define MS_MAX_CMDSETS 32
static ms_cmdset *cmdsets[MS_MAX_CMDSETS];
static int ncmdsets;

static ms_cmdset *find_set(const char *name)
{
    for (int i = 0; i < ncmdsets; i++)
        if (!strcmp(cmdsets[i]->name, name)) return cmdsets[i];
    return NULL;
}

/* The table's entry for objv[1] (or the fallback) gets the words; a missing or unknown word
 * is the argument layer's error. */
static int cmdset_proc(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_cmdset *s = cd;
    int k = objc > 1 ? ms_args_find(s->items, sizeof *s->items, Tcl_GetString(objv[1])) : -1;
    if (k < 0 && (objc < 2 || !s->fallback.fn))
        return ms_args_dispatch(s->app, interp, objc, objv, 1, s->items, NULL, s->name);
    if (!s->quiet && (k < 0 || !s->quiet_items[k])) s->app->world.scene_version++;
    if (k < 0) return ms_args_call(s->app, interp, objc, objv, 1, &s->fallback, s->name, 1);
    return ms_args_call(s->app, interp, objc, objv, 2, &s->items[k], s->name, 0);
}

static int extend(const char *name, const ms_subcmd *table, int quiet)
{
    ms_cmdset *s = find_set(name);
    if (!s) return -1;
    for (const ms_subcmd *t = table; t->name; t++) {
        size_t cap = s->cap;
        if (ms_grow((void **)&s->items, &s->cap, s->n + 2, sizeof *s->items)) return -1;
        if (s->cap != cap) {
            unsigned char *q = realloc(s->quiet_items, s->cap);
            if (!q) return -1;
            s->quiet_items = q;
        }
        s->quiet_items[s->n] = (unsigned char)quiet;
        s->items[s->n++] = *t;
        memset(&s->items[s->n], 0, sizeof *s->items);
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
    if (!s || !(s->name = ms_strdup(name)) ||
        ms_grow((void **)&s->items, &s->cap, 1, sizeof *s->items) ||
        !(s->quiet_items = calloc(s->cap, 1))) {
        if (s) free(s->items), free(s->name);
        free(s);
        return NULL;
    }
    memset(s->items, 0, sizeof *s->items);   /* the table's end */
    s->app = app;
    cmdsets[ncmdsets++] = s;
    if (table) extend(name, table, 0);
    Tcl_CreateObjCommand(app->interp, name, cmdset_proc, s, cmdset_delete);
    return s;
}

void ms_cmdset_fallback(ms_app *app, const char *name, const ms_subcmd *entry)
{
    ms_cmdset *s = find_set(name);
    if (s) s->fallback = *entry;
}

void ms_cmdset_quiet(ms_app *app, const char *name)
{
    ms_cmdset *s = find_set(name);
    if (s) s->quiet = 1;
}

/* ---------------------------------------------------------------- plain commands */

typedef struct plain_cmd {
    ms_app *app;
    const ms_subcmd *spec;
} plain_cmd;

static int plain_proc(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const plain_cmd *c = cd;
    return ms_args_call(c->app, interp, objc, objv, 1, c->spec, c->spec->name, 1);
}

static void plain_delete(ClientData cd) { free(cd); }

void ms_cmd_create(ms_app *app, const ms_subcmd *spec)
{
    plain_cmd *c = malloc(sizeof *c);
    if (!c) return;
    c->app = app;
    c->spec = spec;
    Tcl_CreateObjCommand(app->interp, spec->name, plain_proc, c, plain_delete);
}

/* ---------------------------------------------------------------- molecules */

/* A molspec naming exactly one molecule (`all` with one loaded, `active` ...), as VMD takes
 * one wherever it wants a molecule id. */
static ms_molecule *one_of_spec(ms_app *app, Tcl_Interp *interp, const char *w, const char *cmd)
{
    int *ids, n;
    if (ms_cmd_molspec(app, interp, w, cmd, &ids, &n) != TCL_OK) {
        ms_cmd_error(interp, "%s: '%s' is not a molecule id", cmd, w);
        return NULL;
    }
    ms_molecule *m = n == 1 ? ms_molset_get(&app->mols, ids[0]) : NULL;
    free(ids);
    if (!m)
        ms_cmd_error(interp, "%s: '%s' names %d molecules; it operates on one molecule only", cmd,
                     w, n);
    return m;
}

int ms_cmd_frames_appended(ms_app *app, ms_molecule *m)
{
    int id = m->id;
    ms_molset_emit(&app->mols, MS_EV_FRAMES_ADDED, m, NULL);
    if (ms_molset_get(&app->mols, id) != m) return -1;
    ms_molset_set_frame(&app->mols, m, (long)m->nframes - 1);
    if (ms_molset_get(&app->mols, id) != m) return -1;
    if (m->nframes == 1) ms_view_reset(&app->world);   /* its first coordinates, as VMD */
    return 0;
}

ms_molecule *ms_cmd_mol(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, const char *cmd)
{
    const char *w = Tcl_GetString(word);
    if (ms_word_eq(w, "top")) {
        ms_molecule *m = ms_molset_top(&app->mols);
        if (!m) ms_cmd_error(interp, "%s: no molecules are loaded (no top molecule)", cmd);
        return m;
    }
    int id;
    if (Tcl_GetIntFromObj(NULL, word, &id) != TCL_OK) return one_of_spec(app, interp, w, cmd);
    ms_molecule *m = ms_molset_get(&app->mols, id);
    if (!m) ms_cmd_error(interp, "%s: no molecule with id %d", cmd, id);
    return m;
}

/* The molspec words; the second spelling of a pair means the same. */
typedef enum { SPEC_ALL, SPEC_NONE, SPEC_TOP, SPEC_ACTIVE, SPEC_INACTIVE, SPEC_DISPLAYED, SPEC_ON,
               SPEC_OFF, SPEC_FIXED, SPEC_FREE, SPEC_UNFIX } spec_word;
static const char *const spec_words[] = {"all", "none", "top", "active", "inactive",
                                         "displayed", "on", "off", "fixed", "free", "unfix",
                                         NULL};

/* Does molecule m match molspec word k? */
static int spec_match(const ms_molecule *m, spec_word k, int top)
{
    switch (k) {
    case SPEC_ALL: return 1;
    case SPEC_NONE: return 0;
    case SPEC_TOP: return m->id == top;
    case SPEC_ACTIVE: return m->active;
    case SPEC_INACTIVE: return !m->active;
    case SPEC_DISPLAYED: case SPEC_ON: return m->displayed;
    case SPEC_OFF: return !m->displayed;
    case SPEC_FIXED: return m->fixed;
    case SPEC_FREE: case SPEC_UNFIX: return !m->fixed;
    }
    return 0;
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
        } else {
            int k = ms_args_find(spec_words, sizeof *spec_words, w);
            if (k < 0) {
                rc = ms_cmd_error(interp, "%s: bad molecule specification '%s'", cmd, w);
                goto done;
            }
            for (size_t i = 0; i < nm; i++)
                if (spec_match(app->mols.mols[i], (spec_word)k, app->mols.top)) chosen[i] = 1;
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

/* ---------------------------------------------------------------- loading */

/* VMD's load options; waitfor is a number or `all`, read after the table. */
typedef struct load_args {
    ms_load_opts o;
    Tcl_Obj *waitfor;
} load_args;

#define LOFF(f) offsetof(load_args, f)
static const ms_opt load_options[] = {
    {"type", MS_OPT_STRING, LOFF(o.type), 0, 0, 0, NULL},
    {"first", MS_OPT_LONG, LOFF(o.first), 0, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"beg", MS_OPT_LONG, LOFF(o.first), 0, INT_MAX, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_ALIAS, NULL},
    {"last", MS_OPT_LONG, LOFF(o.last), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"end", MS_OPT_LONG, LOFF(o.last), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_ALIAS, NULL},
    {"step", MS_OPT_LONG, LOFF(o.step), 1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"skip", MS_OPT_LONG, LOFF(o.step), 1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_ALIAS, NULL},
    {"waitfor", MS_OPT_OBJ, LOFF(waitfor), 0, 0, 0, NULL},
    {"filebonds", MS_OPT_BOOL, LOFF(o.filebonds), 0, 0, 0, NULL},
    {"autobonds", MS_OPT_BOOL, LOFF(o.autobonds), 0, 0, 0, NULL},
    {"volsets", MS_OPT_IGNORE, 0, 0, 0, 0, NULL},   /* every data set of a volume file is read */
    {"assembly", MS_OPT_STRING, LOFF(o.assembly), 0, 0, 0, NULL},
    {"bcast", MS_OPT_BOOL, LOFF(o.bcast), 0, 0, 0, NULL},
    /* molscope's own: frames read on demand through a window of -window frames */
    {"-stream", MS_OPT_FLAG, LOFF(o.stream), 0, 0, 0, NULL},
    {"-window", MS_OPT_LONG, LOFF(o.window), 2, 100000, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

int ms_cmd_parse_load_opts(Tcl_Interp *interp, const char *cmd, int objc, Tcl_Obj *const objv[],
                           int start, ms_load_opts *o, Tcl_Obj **molid_word)
{
    load_args a = {*o, NULL};
    if (ms_args_options(interp, objc, objv, start, load_options, &a, molid_word) != TCL_OK)
        return TCL_ERROR;
    static const char *const all[] = {"all", NULL};
    int k;
    if (a.waitfor &&
        ms_arg_long_or(interp, a.waitfor, "waitfor", all, -1, INT_MAX, &k, &a.o.waitfor))
        return TCL_ERROR;
    if (a.waitfor && k == 0) a.o.waitfor = -1;
    if (a.o.last >= 0 && a.o.last < a.o.first)
        return ms_cmd_error(interp, "%s: last frame %ld comes before first frame %ld", cmd,
                            a.o.last, a.o.first);
    *o = a.o;
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

/* Say once why a molecule's frames stream when it was not asked (they would not fit). */
static void announce_stream(ms_molecule *m)
{
    if (!m->stream || !m->stream->why[0]) return;
    printf("Info) molecule %d: %s: its frames are read from the file when needed, %zu at "
           "most kept in memory\n", m->id, m->stream->why, m->stream->window);
    fflush(stdout);
    m->stream->why[0] = '\0';
}

/* Remember the options the molecule's last file was read with (molinfo filespec). */
static void keep_spec(ms_molecule *m, const ms_load_opts *o)
{
    if (!m->nfiles) return;
    ms_molfile *f = &m->files[m->nfiles - 1];
    f->first = o->first;
    f->last = o->last;
    f->step = o->step;
    f->filebonds = o->filebonds;
    f->autobonds = o->autobonds;
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
        keep_spec(m, o);
        announce_stream(m);
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
    /* Files load in order: the frames still pending from an earlier file come first (a
     * damage found there is that file's, reported as a background error). */
    if (into->pending && ms_app_finish_molecule(app, into))
        return ms_cmd_error(interp, "%s: %s: the molecule was deleted while its earlier "
                            "file was being read", cmd, path);
    size_t atoms_before = into->atoms.n, frames_before = into->nframes;
    size_t volumes_before = into->nvolumes;
    if (bcast ? ms_par_load_add(&app->plugins, into, path, o, &err)
              : ms_load_add(&app->plugins, into, path, o, &err))
        return ms_cmd_error(interp, "%s: %s: %s", cmd, path, err.msg);
    keep_spec(into, o);
    announce_stream(into);
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
        /* a structure given its first coordinates (a PSF, then a DCD): VMD resets the view */
        if (frames_before == 0 && atoms_before > 0) ms_view_reset(&app->world);
    }
    if (into->pending) ms_app_schedule_loading(app);
    else ms_molset_emit(&app->mols, MS_EV_TRAJ_DONE, into, path);
    Tcl_SetObjResult(interp, Tcl_NewIntObj(into->id));
    return TCL_OK;
}
