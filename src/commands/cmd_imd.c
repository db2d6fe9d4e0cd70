/* cmd_imd.c: VMD's `imd` command: Interactive Molecular Dynamics, a running simulation
 * (NAMD, GROMACS, LAMMPS) streaming the top molecule's coordinates over TCP (the protocol:
 * imd/imd.h).
 *
 *   imd connect <host> <port>    connect, handshake, IMD_GO; frames then arrive on the Tcl
 *                                event loop (vwait, after, update keep working)
 *   imd pause ?on|off|toggle?    pause or resume the simulation (IMD_PAUSE; default toggle)
 *   imd detach                   leave the simulation running (IMD_DISCONNECT)
 *   imd kill                     stop the simulation (IMD_KILL)
 *   imd transfer ?<rate>?        send coordinates every <rate> steps (IMD_TRATE); the rate
 *   imd keep ?<rate>?            0: each frame replaces the last frame; N: every Nth frame
 *                                starts a new frame (the frames between update it); the rate
 *   imd copyunitcell ?on|off?    new frames take the unit cell of the frame before
 *   imd energies                 the last IMD_ENERGIES (molscope's addition), as molinfo names
 *
 * A frame takes the last energies received before its coordinates (VMD's rule; GROMACS sends
 * a step's energies first): molinfo's bond ... energy keywords read them.
 *
 * Errors while streaming (the simulation closes, a wrong message, a coordinate count that is
 * not the molecule's) end the session and go to the background error handler. */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"
#include "imd/imd.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define ASSOC "molscope::imd"
#define IMD_TIMEOUT 5.0            /* seconds for the connection and for the handshake */
#define IMD_READ_SIZE (1u << 20)   /* bytes of one read */
#define IMD_READS_PER_TURN 16      /* reads per turn of the event loop at most */

typedef struct imd_session {
    ms_app *app;
    int fd;                        /* -1: not connected */
    int molid;
    char where[300];               /* host:port */
    ms_imd_decoder dec;
    int keep, trate, copycell, paused;
    long received;                 /* frames of this session */
    int have_energies;
    ms_imd_energies energies;
    unsigned char *buf;
    unsigned gen;                  /* sessions ended: a Tcl callback may end one mid-read */
    int busy;                      /* reading: a nested event loop must not read again */
} imd_session;

static imd_session *session_of(ms_app *app)
{
    return Tcl_GetAssocData(app->interp, ASSOC, NULL);
}

/* End the connection (no message sent). */
static void session_close(imd_session *s)
{
    if (s->fd < 0) return;
    Tcl_DeleteFileHandler(s->fd);
    close(s->fd);
    s->fd = -1;
    s->gen++;
    ms_imd_decoder_free(&s->dec);
}

/* Send a bodiless message and end the connection either way: 0, or -1 with err when the
 * message could not be sent (the simulation may have gone already). */
static int session_end(imd_session *s, int32_t type, ms_error *err)
{
    int rc = ms_imd_send(s->fd, type, 0, err);
    session_close(s);
    return rc;
}

/* An error while streaming: the session ends and the background error handler hears it. */
static void stream_failed(imd_session *s, const ms_error *err)
{
    Tcl_Interp *interp = s->app->interp;
    Tcl_Obj *msg = Tcl_ObjPrintf("imd: %s: %s; disconnected", s->where, err->msg);
    session_close(s);
    Tcl_InterpState saved = Tcl_SaveInterpState(interp, TCL_OK);
    Tcl_SetObjResult(interp, msg);
    Tcl_BackgroundException(interp, TCL_ERROR);
    Tcl_RestoreInterpState(interp, saved);
}

/* ---------------------------------------------------------------- frames */

/* The frame a new set of coordinates goes to: a new one every keep-th frame (or when the
 * molecule has none), else the last. *added says which. */
static ms_frame *target_frame(imd_session *s, ms_molecule *m, int *added, ms_error *err)
{
    s->received++;
    *added = m->nframes == 0 || (s->keep > 0 && s->received % s->keep == 0);
    if (!*added) return &m->frames[m->nframes - 1];
    ms_frame *f = ms_mol_add_frame(m, 0, err);
    if (!f) return NULL;
    memset(f->cell, 0, sizeof f->cell);
    if (s->copycell && m->nframes > 1)
        memcpy(f->cell, m->frames[m->nframes - 2].cell, sizeof f->cell);
    return f;
}

/* The last energies received into a frame's terms, as VMD fills its timestep (kinetic is
 * total - potential; IMD sends no H-bond or field term). */
static void put_energies(const ms_imd_energies *e, float out[MS_EN_KINDS])
{
    memset(out, 0, sizeof(float[MS_EN_KINDS]));
    out[MS_EN_BOND] = e->Ebond;
    out[MS_EN_ANGLE] = e->Eangle;
    out[MS_EN_DIHEDRAL] = e->Edihe;
    out[MS_EN_IMPROPER] = e->Eimpr;
    out[MS_EN_VDW] = e->Evdw;
    out[MS_EN_ELEC] = e->Eelec;
    out[MS_EN_KINETIC] = e->Etot - e->Epot;
    out[MS_EN_POTENTIAL] = e->Epot;
    out[MS_EN_TEMPERATURE] = e->T;
    out[MS_EN_TOTAL] = e->Etot;
}

static int apply_coords(imd_session *s, const float *xyz, ms_error *err)
{
    ms_app *app = s->app;
    ms_molecule *m = ms_molset_get(&app->mols, s->molid);
    if (!m) {
        ms_error_set(err, "molecule %d was deleted", s->molid);
        return -1;
    }
    if (m->atoms.n != s->dec.natoms) {
        ms_error_set(err, "molecule %d now has %zu atoms, the simulation %zu", s->molid,
                     m->atoms.n, s->dec.natoms);
        return -1;
    }
    int added;
    ms_frame *f = target_frame(s, m, &added, err);
    if (!f) return -1;
    memcpy(f->pos, xyz, m->atoms.n * 3 * sizeof(float));
    if (s->have_energies) put_energies(&s->energies, f->energy);
    app->world.scene_version++;
    if (!added) {
        ms_molset_emit(&app->mols, MS_EV_FRAME, m, NULL);
        return 0;
    }
    ms_cmd_frames_appended(app, m);
    return 0;
}

/* A whole message: 0, 1 when the simulation ended the session, -1 with err. */
static int handle_msg(imd_session *s, const ms_imd_msg *msg, ms_error *err)
{
    switch (msg->type) {
    case MS_IMD_FCOORDS:
        return apply_coords(s, msg->coords, err);
    case MS_IMD_ENERGIES:
        s->energies = msg->energies;
        s->have_energies = 1;
        return 0;
    case MS_IMD_DISCONNECT: case MS_IMD_KILL:
        session_close(s);
        return 1;
    default:
        return 0;
    }
}

/* Decode and apply n bytes of s->buf: 0, 1 when the session ended (an error reported, or a
 * Tcl callback of the frame's events ended it). */
static int take_bytes(imd_session *s, long n)
{
    ms_error err = {{0}};
    unsigned gen = s->gen;
    for (long at = 0; at < n;) {
        ms_imd_msg msg;
        int done, rc = 0;
        long used = ms_imd_feed(&s->dec, s->buf + at, (size_t)(n - at), &msg, &done, &err);
        if (used < 0 || (done && (rc = handle_msg(s, &msg, &err)) < 0)) {
            stream_failed(s, &err);
            return 1;
        }
        if (rc || s->gen != gen) return 1;
        at += used;
    }
    return 0;
}

/* The socket is readable: what has arrived, up to IMD_READS_PER_TURN buffers, so a fast
 * simulation cannot hold the event loop. */
static void on_readable(ClientData cd, int mask)
{
    (void)mask;
    imd_session *s = cd;
    if (s->busy) return;           /* the socket stays readable: the outer call goes on */
    s->busy = 1;
    for (int i = 0; i < IMD_READS_PER_TURN; i++) {
        ms_error err = {{0}};
        long n = ms_imd_recv_now(s->fd, s->buf, IMD_READ_SIZE, &err);
        if (n < 0) stream_failed(s, &err);
        if (n <= 0 || take_bytes(s, n)) break;
    }
    s->busy = 0;
}

/* ---------------------------------------------------------------- subcommands */

static imd_session *connected(ms_app *app, Tcl_Interp *interp)
{
    imd_session *s = session_of(app);
    if (s->fd < 0) {
        ms_cmd_error(interp, "%s: not connected to a simulation", ms_args_where());
        return NULL;
    }
    return s;
}

/* Open the session on molecule m: connect, handshake, the rate if one was set. */
static int session_open(imd_session *s, ms_molecule *m, const char *host, int port,
                        ms_error *err)
{
    int swap;
    s->fd = ms_imd_connect(host, port, IMD_TIMEOUT, err);
    if (s->fd < 0) return -1;
    if (ms_imd_handshake(s->fd, IMD_TIMEOUT, &swap, err) ||
        ms_imd_decoder_init(&s->dec, m->atoms.n, swap, err) ||
        (s->trate != 1 && ms_imd_send(s->fd, MS_IMD_TRATE, s->trate, err))) {
        close(s->fd);
        s->fd = -1;
        return -1;
    }
    return 0;
}

static int imd_connect(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    imd_session *s = session_of(app);
    int port;
    if (s->fd >= 0)
        return ms_cmd_error(interp, "imd connect: already connected to %s (imd detach first)",
                            s->where);
    if (ms_arg_int(interp, objv[3], "port", 1, 65535, &port)) return TCL_ERROR;
    ms_molecule *m = ms_molset_top(&app->mols);
    if (!m)
        return ms_cmd_error(interp, "imd connect: no molecule: load the simulated structure "
                            "first (IMD updates the top molecule)");
    const char *host = Tcl_GetString(objv[2]);
    ms_error err = {{0}};
    if (session_open(s, m, host, port, &err))
        return ms_cmd_error(interp, "imd connect: %s", err.msg);
    snprintf(s->where, sizeof s->where, "%.255s:%d", host, port);
    s->molid = m->id;
    s->received = 0;
    s->paused = 0;
    s->have_energies = 0;
    Tcl_CreateFileHandler(s->fd, TCL_READABLE, on_readable, s);
    return TCL_OK;
}

static int imd_pause(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const char *const modes[] = {"toggle", "on", "off", NULL};
    int mode = 0;
    imd_session *s = connected(app, interp);
    if (!s || (objc > 2 && ms_arg_choice(interp, objv[2], modes, "pause", &mode)))
        return TCL_ERROR;
    int want = mode == 0 ? !s->paused : mode == 1;
    ms_error err = {{0}};
    if (want != s->paused && ms_imd_send(s->fd, MS_IMD_PAUSE, 0, &err))
        return ms_cmd_error(interp, "imd pause: %s", err.msg);
    s->paused = want;
    return TCL_OK;
}

/* imd detach, imd kill. */
static int imd_leave(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    imd_session *s = connected(app, interp);
    if (!s) return TCL_ERROR;
    int kill = ms_word_eq(Tcl_GetString(objv[1]), "kill");
    ms_error err = {{0}};
    /* detaching from a simulation that is gone already is no error; a kill not sent is */
    if (session_end(s, kill ? MS_IMD_KILL : MS_IMD_DISCONNECT, &err) && kill)
        return ms_cmd_error(interp, "imd kill: %s (disconnected)", err.msg);
    return TCL_OK;
}

static int imd_transfer(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    imd_session *s = session_of(app);
    int rate;
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(s->trate));
        return TCL_OK;
    }
    if (ms_arg_int(interp, objv[2], "rate", 1, INT32_MAX, &rate)) return TCL_ERROR;
    ms_error err = {{0}};
    if (s->fd >= 0 && ms_imd_send(s->fd, MS_IMD_TRATE, rate, &err))
        return ms_cmd_error(interp, "imd transfer: %s", err.msg);
    s->trate = rate;
    return TCL_OK;
}

static int imd_keep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    imd_session *s = session_of(app);
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(s->keep));
        return TCL_OK;
    }
    return ms_arg_int(interp, objv[2], "rate", 0, INT32_MAX, &s->keep);
}

static int imd_copyunitcell(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    imd_session *s = session_of(app);
    if (objc == 2) {
        Tcl_SetObjResult(interp, Tcl_NewStringObj(s->copycell ? "on" : "off", -1));
        return TCL_OK;
    }
    return ms_arg_bool(interp, objv[2], "copyunitcell", &s->copycell);
}

static int imd_energies(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    (void)objv;
    imd_session *s = session_of(app);
    Tcl_Obj *r = Tcl_NewListObj(0, NULL);
    if (s->have_energies) {
        const ms_imd_energies *e = &s->energies;
        const char *names[] = {"temperature", "energy", "potential", "vdw", "elec", "bond",
                               "angle", "dihedral", "improper"};
        const float v[] = {e->T, e->Etot, e->Epot, e->Evdw, e->Eelec, e->Ebond, e->Eangle,
                           e->Edihe, e->Eimpr};
        Tcl_ListObjAppendElement(NULL, r, Tcl_NewStringObj("timestep", -1));
        Tcl_ListObjAppendElement(NULL, r, Tcl_NewLongObj(e->tstep));
        for (size_t i = 0; i < MS_COUNTOF(v); i++) {
            Tcl_ListObjAppendElement(NULL, r, Tcl_NewStringObj(names[i], -1));
            Tcl_ListObjAppendElement(NULL, r, Tcl_NewDoubleObj(v[i]));
        }
    }
    Tcl_SetObjResult(interp, r);
    return TCL_OK;
}

/* ---------------------------------------------------------------- registration */

static void on_interp_delete(ClientData cd, Tcl_Interp *interp)
{
    (void)interp;
    imd_session *s = cd;
    session_close(s);
    free(s->buf);
    free(s);
}

void ms_cmd_imd_register(ms_app *app)
{
    static const ms_subcmd table[] = {
        {"connect", imd_connect, 2, 2, "<host> <port>"},
        {"pause", imd_pause, 0, 1, "?on|off|toggle?"},
        {"detach", imd_leave, 0, 0, ""},
        {"kill", imd_leave, 0, 0, ""},
        {"transfer", imd_transfer, 0, 1, "?<rate>?"},
        {"keep", imd_keep, 0, 1, "?<rate>?"},
        {"copyunitcell", imd_copyunitcell, 0, 1, "?on|off?"},
        {"energies", imd_energies, 0, 0, ""},
        {NULL, NULL, 0, 0, NULL}};
    imd_session *s = calloc(1, sizeof *s);
    unsigned char *buf = malloc(IMD_READ_SIZE);
    if (!s || !buf) {
        free(s);
        free(buf);
        return;
    }
    s->app = app;
    s->fd = -1;
    s->trate = 1;
    s->buf = buf;
    Tcl_SetAssocData(app->interp, ASSOC, on_interp_delete, s);
    ms_cmdset_create(app, "imd", table);
    ms_cmdset_quiet(app, "imd");
}
