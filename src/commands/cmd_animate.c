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
#include <string.h>
#include <strings.h>

typedef enum { ANIM_ONCE, ANIM_ROCK, ANIM_LOOP } anim_style;
static const char *style_names[] = {"Once", "Rock", "Loop"};

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
    if (objc != 3) return ms_cmd_error(interp, "animate goto: usage: animate goto start|end|<frame>");
    const char *w = Tcl_GetString(objv[2]);
    long target;
    int end = 0;
    if (!strcasecmp(w, "start")) target = 0;
    else if (!strcasecmp(w, "end")) end = 1, target = 0;
    else {
        int v;
        if (Tcl_GetIntFromObj(NULL, objv[2], &v) != TCL_OK)
            return ms_cmd_error(interp, "animate goto: expected start, end or a frame number, got '%s'", w);
        target = v;
    }
    anim_play(app, 0);
    for (size_t i = 0; i < app->mols.n; i++) {
        ms_molecule *m = app->mols.mols[i];
        if (m->active) ms_molset_set_frame(&app->mols, m, end ? (long)m->nframes - 1 : target);
    }
    return TCL_OK;
}

static int an_step(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    if (objc != 2) return ms_cmd_error(interp, "animate %s: takes no arguments", w);
    if (!strcasecmp(w, "next")) { anim_play(app, 0); step_active(app, anim.skip); }
    else if (!strcasecmp(w, "prev")) { anim_play(app, 0); step_active(app, -anim.skip); }
    else if (!strcasecmp(w, "forward") || !strcasecmp(w, "for")) anim_play(app, 1);
    else if (!strcasecmp(w, "reverse") || !strcasecmp(w, "rev")) anim_play(app, -1);
    else anim_play(app, 0);
    return TCL_OK;
}

static int an_style(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(style_names[anim.style], -1));
        return TCL_OK;
    }
    if (objc != 3) return ms_cmd_error(interp, "animate style: usage: animate style ?once|rock|loop?");
    const char *w = Tcl_GetString(objv[2]);
    for (int s = 0; s < 3; s++)
        if (!strcasecmp(w, style_names[s])) {
            anim.style = (anim_style)s;
            return TCL_OK;
        }
    return ms_cmd_error(interp, "animate style: unknown style '%s': must be once, rock or loop", w);
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
    if (objc == 3) {
        double v;
        if (Tcl_GetDoubleFromObj(NULL, objv[2], &v) != TCL_OK || v < 0 || v > 1)
            return ms_cmd_error(interp, "animate speed: expected a number from 0 to 1, got '%s'",
                                Tcl_GetString(objv[2]));
        anim.speed = v;
    } else if (objc != 2) {
        return ms_cmd_error(interp, "animate speed: usage: animate speed ?0..1?");
    }
    Tcl_SetObjResult(interp, Tcl_NewDoubleObj(anim.speed));
    return TCL_OK;
}

static int an_skip(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 3) {
        int v;
        if (Tcl_GetIntFromObj(NULL, objv[2], &v) != TCL_OK || v < 1)
            return ms_cmd_error(interp, "animate skip: expected a positive integer, got '%s'",
                                Tcl_GetString(objv[2]));
        anim.skip = v;
    } else if (objc != 2) {
        return ms_cmd_error(interp, "animate skip: usage: animate skip ?n?");
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(anim.skip));
    return TCL_OK;
}

static int an_read(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc < 4)
        return ms_cmd_error(interp, "animate read: usage: animate read <type> <file> ?beg b? ?end e? "
                                    "?skip s? ?waitfor n|all? ?molid?");
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

/* Frame range options beg/end/skip (and waitfor, sel where allowed) then an optional molid. */
typedef struct frame_range {
    long beg, end, skip;
    const char *sel;
    Tcl_Obj *molword;
    int all;
} frame_range;

static int parse_range(Tcl_Interp *interp, const char *cmd, int objc, Tcl_Obj *const objv[],
                       int start, int allow_sel, frame_range *r)
{
    memset(r, 0, sizeof *r);
    r->end = -1;
    r->skip = 1;
    for (int i = start; i < objc; i++) {
        const char *w = Tcl_GetString(objv[i]);
        if (!strcasecmp(w, "all")) { r->all = 1; continue; }
        if (i + 1 >= objc) {
            r->molword = objv[i];
            break;
        }
        Tcl_Obj *v = objv[++i];
        long *dst = !strcasecmp(w, "beg") || !strcasecmp(w, "first") ? &r->beg
                  : !strcasecmp(w, "end") || !strcasecmp(w, "last") ? &r->end
                  : !strcasecmp(w, "skip") || !strcasecmp(w, "step") ? &r->skip : NULL;
        if (dst) {
            int x;
            if (Tcl_GetIntFromObj(NULL, v, &x) != TCL_OK || x < (dst == &r->end ? -1 : dst == &r->skip ? 1 : 0))
                return ms_cmd_error(interp, "%s: bad value '%s' for %s", cmd, Tcl_GetString(v), w);
            *dst = x;
        } else if (!strcasecmp(w, "waitfor")) {
            /* writing always waits for every frame; accepted for compatibility */
        } else if (allow_sel && !strcasecmp(w, "sel")) {
            r->sel = Tcl_GetString(v);
        } else {
            return ms_cmd_error(interp, "%s: unknown option '%s'", cmd, w);
        }
    }
    return TCL_OK;
}

static int an_write(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc < 4)
        return ms_cmd_error(interp, "animate write: usage: animate write <type> <file> ?beg b? "
                                    "?end e? ?skip s? ?waitfor n|all? ?sel sel? ?molid?");
    frame_range r;
    if (parse_range(interp, "animate write", objc, objv, 4, 1, &r)) return TCL_ERROR;
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
    if (parse_range(interp, "animate delete", objc, objv, 2, 0, &r)) return TCL_ERROR;
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
    if (objc != 3 && objc != 5)
        return ms_cmd_error(interp, "animate dup: usage: animate dup ?frame <n|now|null>? <molid>");
    ms_molecule *m = ms_cmd_mol(app, interp, objv[objc - 1], "animate dup");
    if (!m) return TCL_ERROR;
    long src = m->frame;
    if (objc == 5) {
        const char *w = Tcl_GetString(objv[3]);
        if (strcasecmp(Tcl_GetString(objv[2]), "frame"))
            return ms_cmd_error(interp, "animate dup: expected 'frame', got '%s'", Tcl_GetString(objv[2]));
        int v;
        if (!strcasecmp(w, "now")) src = m->frame;
        else if (!strcasecmp(w, "null")) src = -1;
        else if (Tcl_GetIntFromObj(NULL, objv[3], &v) == TCL_OK && v >= 0 && (size_t)v < m->nframes) src = v;
        else return ms_cmd_error(interp, "animate dup: molecule %d has no frame '%s'", m->id, w);
    }
    ms_error err = {{0}};
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
    } else {
        memset(f->pos, 0, bytes);
    }
    ms_molset_emit(&app->mols, MS_EV_FRAMES_ADDED, m, NULL);
    ms_molset_set_frame(&app->mols, m, (long)m->nframes - 1);
    return TCL_OK;
}

static const ms_subcmd animate_table[] = {
    {"goto", an_goto},      {"next", an_step},     {"prev", an_step},   {"forward", an_step},
    {"for", an_step},       {"reverse", an_step},  {"rev", an_step},    {"pause", an_step},
    {"style", an_style},    {"styles", an_styles}, {"speed", an_speed}, {"skip", an_skip},
    {"read", an_read},      {"write", an_write},   {"delete", an_delete}, {"dup", an_dup},
    {NULL, NULL}};

void ms_cmd_animate_register(ms_app *app)
{
    anim.app = app;
    ms_cmdset_create(app, "animate", animate_table);
}
