/* cmd_animate.c: the `animate` command: moving through frames, playing animations, reading,
 * writing, deleting and duplicating frames.
 *
 *   animate goto start|end|n; next; prev; forward|for; reverse|rev; pause
 *   animate style ?once|rock|loop?; speed ?0..1?; skip ?n?; styles
 *   animate read type file ?beg b? ?end e? ?skip s? ?waitfor n|all? ?molid?
 *   animate write type file ?beg b? ?end e? ?skip s? ?waitfor n|all? ?sel sel? ?molid?
 *   animate delete all ?molid? | animate delete ?beg b? ?end e? ?skip s? ?molid?
 *   animate dup ?frame n|now|null? molid */
#include "config.h"
#include "commands/atomsel.h"
#include "commands/commands.h"
#include "fileio/load.h"
#include "fileio/write.h"

#include <stdlib.h>
#include <limits.h>
#include <stddef.h>
#include <string.h>

typedef enum { ANIM_ONCE, ANIM_ROCK, ANIM_LOOP } anim_style;
static const char *const style_names[] = {"Once", "Rock", "Loop", NULL};

static struct {
    anim_style style;
    double speed;
    int skip;
    int dir;                 /* -1 reverse, 0 paused, +1 forward */
    Tcl_TimerToken timer;
    ms_app *app;
} anim = {ANIM_LOOP, 1.0, 1, 0, NULL, NULL};

/* Step one molecule by n frames following the animation style. */
static void step_molecule(ms_app *app, ms_molecule *m, int n)
{
    long nf = (long)m->nframes;
    if (nf <= 1) return;
    long f = m->frame + n;
    if (f >= nf || f < 0) {
        switch (anim.style) {
        case ANIM_LOOP: f = ((f % nf) + nf) % nf; break;
        case ANIM_ONCE: f = f < 0 ? 0 : nf - 1; anim.dir = 0; break;
        case ANIM_ROCK:
            anim.dir = -anim.dir;
            f = f < 0 ? MS_MIN(-f, nf - 1) : MS_MAX(0, 2 * (nf - 1) - f);
            break;
        }
    }
    ms_molset_set_frame(&app->mols, m, f);
}

static void step_active(ms_app *app, int n)
{
    for (size_t i = 0; i < app->mols.n; i++)
        if (app->mols.mols[i]->active) step_molecule(app, app->mols.mols[i], n);
}

static void anim_tick(ClientData cd)
{
    ms_app *app = cd;
    anim.timer = NULL;
    if (anim.dir == 0) return;
    step_active(app, anim.dir * anim.skip);
    if (anim.dir != 0)
        anim.timer = Tcl_CreateTimerHandler((int)((1.0 - anim.speed) * 500.0) + 1, anim_tick, app);
}

static void anim_play(ms_app *app, int dir)
{
    anim.dir = dir;
    if (anim.timer) Tcl_DeleteTimerHandler(anim.timer);
    anim.timer = dir ? Tcl_CreateTimerHandler(1, anim_tick, app) : NULL;
}

static int an_goto(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const words[] = {"start", "end", NULL};
    long target = 0;
    int word;
    if (ms_arg_long_or(interp, objv[2], "frame", words, INT_MIN, INT_MAX, &word, &target))
        return TCL_ERROR;
    int end = word == 1;
    anim_play(app, 0);
    ms_error err = {{0}};
    for (size_t i = 0; i < app->mols.n; i++) {
        ms_molecule *m = app->mols.mols[i];
        if (m->active &&
            ms_molset_goto(&app->mols, m, end ? (long)m->nframes - 1 : target, &err))
            return ms_cmd_error(interp, "animate goto: %s", err.msg);
    }
    return TCL_OK;
}

static int an_next(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    anim_play(app, 0);
    step_active(app, anim.skip);
    return TCL_OK;
}

static int an_prev(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    anim_play(app, 0);
    step_active(app, -anim.skip);
    return TCL_OK;
}

static int an_forward(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    anim_play(app, 1);
    return TCL_OK;
}

static int an_reverse(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    anim_play(app, -1);
    return TCL_OK;
}

static int an_pause(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    anim_play(app, 0);
    return TCL_OK;
}

static int an_style(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(style_names[anim.style], -1));
        return TCL_OK;
    }
    int s;
    if (ms_arg_choice(interp, objv[2], style_names, "style", &s)) return TCL_ERROR;
    anim.style = (anim_style)s;
    return TCL_OK;
}

static int an_styles(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int s = 0; s < 3; s++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(style_names[s], -1));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int an_speed(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 3 && ms_arg_double_range(interp, objv[2], NULL, 0, 1, &anim.speed))
        return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewDoubleObj(anim.speed));
    return TCL_OK;
}

static int an_skip(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 3 && ms_arg_int(interp, objv[2], NULL, 1, INT_MAX, &anim.skip)) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewIntObj(anim.skip));
    return TCL_OK;
}

static int an_read(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_load_opts o;
    ms_load_opts_default(&o);
    Tcl_Obj *molword;
    if (ms_cmd_parse_load_opts(interp, "animate read", objc, objv, 4, &o, &molword)) return TCL_ERROR;
    o.type = Tcl_GetString(objv[2]);
    ms_molecule *m = molword ? ms_cmd_mol(app, interp, molword, "animate read")
                             : ms_cmd_mol(app, interp, Tcl_NewStringObj("top", -1), "animate read");
    if (!m) return TCL_ERROR;
    return ms_cmd_load(app, interp, "animate read", Tcl_GetString(objv[3]), &o, m);
}

/* Frame range options beg/end/skip, waitfor (ignored: writing waits for every frame), sel
 * where allowed and the word `all`, then an optional molid. */
typedef struct frame_range {
    long beg, end, skip;
    const char *sel;
    Tcl_Obj *molword;
    int all;
} frame_range;

#define ROFF(f) offsetof(frame_range, f)
#define RANGE_OPTIONS                                                         \
    {"all", MS_OPT_FLAG, ROFF(all), 0, 0, 0, NULL},                                       \
    {"beg", MS_OPT_LONG, ROFF(beg), 0, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},           \
    {"first", MS_OPT_LONG, ROFF(beg), 0, INT_MAX, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_ALIAS, NULL}, \
    {"end", MS_OPT_LONG, ROFF(end), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},          \
    {"last", MS_OPT_LONG, ROFF(end), -1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_ALIAS, NULL}, \
    {"skip", MS_OPT_LONG, ROFF(skip), 1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},         \
    {"step", MS_OPT_LONG, ROFF(skip), 1, INT_MAX, MS_OPT_MIN | MS_OPT_MAX | MS_OPT_ALIAS, NULL}, \
    {"waitfor", MS_OPT_IGNORE, 0, 0, 0, 0, NULL}
static const ms_opt write_options[] = {RANGE_OPTIONS,
                                       {"sel", MS_OPT_STRING, ROFF(sel), 0, 0, 0, NULL},
                                       {NULL, 0, 0, 0, 0, 0, NULL}};
static const ms_opt delete_options[] = {RANGE_OPTIONS, {NULL, 0, 0, 0, 0, 0, NULL}};

static int parse_range(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int start,
                       const ms_opt *options, frame_range *r)
{
    memset(r, 0, sizeof *r);
    r->end = -1;
    r->skip = 1;
    return ms_args_options(interp, objc, objv, start, options, r, &r->molword);
}

static int an_write(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    frame_range r;
    if (parse_range(interp, objc, objv, 4, write_options, &r)) return TCL_ERROR;
    ms_molecule *m = ms_cmd_mol(app, interp, r.molword ? r.molword : Tcl_NewStringObj("top", -1),
                                "animate write");
    if (!m) return TCL_ERROR;
    ms_app_finish_loading(app);
    ms_write_opts o;
    ms_write_opts_default(&o);
    o.type = Tcl_GetString(objv[2]);
    o.first = r.beg;
    o.last = r.end;
    o.step = r.skip;
    uint32_t *atoms = NULL;
    if (r.sel) {
        int selmol;
        long selframe;
        size_t n;
        if (ms_atomsel_resolve(app, interp, r.sel, "animate write", &selmol, &selframe, &atoms,
                               &n) != TCL_OK)
            return TCL_ERROR;
        if (selmol != m->id) {
            free(atoms);
            return ms_cmd_error(interp, "animate write: selection %s belongs to molecule %d, not %d",
                                r.sel, selmol, m->id);
        }
        o.atoms = atoms;
        o.natoms = n;
    }
    ms_error err = {{0}};
    long n = ms_write_file(&app->plugins, m, Tcl_GetString(objv[3]), &o, &err);
    free(atoms);
    if (n < 0) return ms_cmd_error(interp, "animate write: %s: %s", Tcl_GetString(objv[3]), err.msg);
    Tcl_SetObjResult(interp, Tcl_NewWideIntObj(n));
    return TCL_OK;
}

static int an_delete(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    frame_range r;
    if (parse_range(interp, objc, objv, 2, delete_options, &r)) return TCL_ERROR;
    ms_molecule *m = ms_cmd_mol(app, interp, r.molword ? r.molword : Tcl_NewStringObj("top", -1),
                                "animate delete");
    if (!m) return TCL_ERROR;
    if (m->nframes == 0) return TCL_OK;
    ms_loader_cancel(m);
    size_t last = r.end < 0 ? m->nframes - 1 : (size_t)r.end;
    if (r.all) ms_mol_delete_frames(m, 0, m->nframes - 1, 1);
    else ms_mol_delete_frames(m, (size_t)r.beg, last, (size_t)r.skip);
    ms_molset_emit(&app->mols, MS_EV_FRAMES_ADDED, m, NULL);
    ms_molset_set_frame(&app->mols, m, m->frame);
    return TCL_OK;
}

static int an_dup(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 4) return ms_args_usage(interp);
    ms_molecule *m = ms_cmd_mol(app, interp, objv[objc - 1], "animate dup");
    if (!m) return TCL_ERROR;
    long src = m->frame;
    if (objc == 5) {
        static const char *const frame_word[] = {"frame", NULL};
        static const char *const words[] = {"now", "null", NULL};
        int k;
        long v;
        if (ms_arg_choice(interp, objv[2], frame_word, NULL, &k)) return TCL_ERROR;
        if (ms_arg_long_or(NULL, objv[3], NULL, words, 0, INT_MAX, &k, &v) == TCL_OK &&
            (k >= 0 || (size_t)v < m->nframes))
            src = k == 0 ? m->frame : k == 1 ? -1 : v;
        else
            return ms_cmd_error(interp, "animate dup: molecule %d has no frame '%s'", m->id,
                                Tcl_GetString(objv[3]));
    }
    ms_error err = {{0}};
    if (src >= 0 && !ms_mol_frame(m, (size_t)src, &err))
        return ms_cmd_error(interp, "animate dup: %s", err.msg);
    int with_vel = src >= 0 && m->frames[src].vel != NULL;
    ms_frame *f = ms_mol_add_frame(m, with_vel, &err);
    if (!f) return ms_cmd_error(interp, "animate dup: %s", err.msg);
    size_t bytes = m->atoms.n * 3 * sizeof(float);
    if (src >= 0) {
        const ms_frame *s = &m->frames[src];
        memcpy(f->pos, s->pos, bytes);
        if (with_vel) memcpy(f->vel, s->vel, bytes);
        memcpy(f->cell, s->cell, sizeof f->cell);
        f->time = s->time;
        memcpy(f->energy, s->energy, sizeof f->energy);
    } else {
        memset(f->pos, 0, bytes);
    }
    ms_cmd_frames_appended(app, m);
    return TCL_OK;
}

static const ms_subcmd animate_table[] = {
    {"goto", an_goto, 1, 1, "start|end|<frame>"},
    {"next", an_next, 0, 0, ""},
    {"prev", an_prev, 0, 0, ""},
    {"forward", an_forward, 0, 0, ""},
    {"for", an_forward, 0, 0, ""},
    {"reverse", an_reverse, 0, 0, ""},
    {"rev", an_reverse, 0, 0, ""},
    {"pause", an_pause, 0, 0, ""},
    {"style", an_style, 0, 1, "?once|rock|loop?"},
    {"styles", an_styles, 0, 0, ""},
    {"speed", an_speed, 0, 1, "?<0..1>?"},
    {"skip", an_skip, 0, 1, "?<n>?"},
    {"read", an_read, 2, MS_ARGS_ANY,
     "<type> <file> ?beg <b>? ?end <e>? ?skip <s>? ?waitfor <n>|all? ?<molid>?"},
    {"write", an_write, 2, MS_ARGS_ANY,
     "<type> <file> ?beg <b>? ?end <e>? ?skip <s>? ?waitfor <n>|all? ?sel <sel>? ?<molid>?"},
    {"delete", an_delete, 0, MS_ARGS_ANY, "all ?<molid>? | ?beg <b>? ?end <e>? ?skip <s>? ?<molid>?"},
    {"dup", an_dup, 1, 3, "?frame <n|now|null>? <molid>"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_animate_register(ms_app *app)
{
    anim.app = app;
    ms_cmdset_create(app, "animate", animate_table);
}
