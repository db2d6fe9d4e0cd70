/* cmd_timestep.c: VMD's commands that move a frame's coordinates as raw bytes (32-bit
 * floats x y z per atom, in the machine's byte order, as a Tcl byte array): fast exchange
 * with `binary scan`/`binary format`, sockets and other programs.
 *
 *   gettimestep <molid> <frame>       the coordinates of a frame (a number, current or last)
 *   rawtimestep <molid> <bytes> ?-frame current|last|new|<n>? ?-start <index>?
 *                                     set coordinates from bytes: 12 of them an atom, from
 *                                     atom index (-start, 0) on, as many atoms as the bytes
 *                                     hold; into a new frame appended (-frame new, the default
 *                                     when the molecule has no frame; it starts as a copy of
 *                                     the last frame, or all zero), else into the frame named
 *                                     (default last) */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"

#include <limits.h>
#include <string.h>

enum { FR_CURRENT, FR_LAST, FR_NEW };

/* A frame word of molecule m: an index in *frame, or FR_NEW's -1 (new allowed only when
 * may_new). */
static int frame_word(Tcl_Interp *interp, const ms_molecule *m, Tcl_Obj *word, int may_new,
                      long *frame)
{
    static const char *const words[] = {"current", "last", "new", NULL};
    int k;
    long v;
    if (ms_arg_long_or(NULL, word, NULL, words, 0, LONG_MAX, &k, &v) != TCL_OK ||
        (k == FR_NEW && !may_new))
        return ms_cmd_error(interp, "%s: bad frame '%s': must be current, last,%s or a frame "
                            "number", ms_args_where(), Tcl_GetString(word),
                            may_new ? " new," : "");
    *frame = k == FR_CURRENT ? m->frame : k == FR_LAST ? (long)m->nframes - 1
             : k == FR_NEW ? -1 : v;
    if (k != FR_NEW && (*frame < 0 || (size_t)*frame >= m->nframes))
        return ms_cmd_error(interp, "%s: molecule %d has no frame '%s' (it has %zu)",
                            ms_args_where(), m->id, Tcl_GetString(word), m->nframes);
    return TCL_OK;
}

static int gettimestep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    (void)objc;
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "gettimestep");
    long f;
    if (!m || frame_word(interp, m, objv[2], 0, &f)) return TCL_ERROR;
    ms_error err = {{0}};
    const float *pos = ms_mol_frame_pos(m, (size_t)f, &err);
    if (!pos) return ms_cmd_error(interp, "gettimestep: %s", err.msg);
    Tcl_SetObjResult(interp, Tcl_NewByteArrayObj((const unsigned char *)pos,
                                                 (int)(m->atoms.n * 3 * sizeof(float))));
    return TCL_OK;
}

typedef struct raw_args {
    Tcl_Obj *frame;
    long start;
} raw_args;

/* A new frame: a copy of the last one's coordinates and cell, or all zero. */
static ms_frame *new_frame(ms_molecule *m, ms_error *err)
{
    if (m->nframes && !ms_mol_frame(m, m->nframes - 1, err)) return NULL;
    ms_frame *f = ms_mol_add_frame(m, 0, err);
    if (!f) return NULL;
    size_t bytes = m->atoms.n * 3 * sizeof(float);
    if (m->nframes > 1) {
        const ms_frame *last = &m->frames[m->nframes - 2];
        memcpy(f->pos, last->pos, bytes);
        memcpy(f->cell, last->cell, sizeof f->cell);
    } else {
        memset(f->pos, 0, bytes);
    }
    return f;
}

static int rawtimestep(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_opt options[] = {
        {"-frame", MS_OPT_OBJ, offsetof(raw_args, frame), 0, 0, 0, NULL},
        {"-start", MS_OPT_LONG, offsetof(raw_args, start), 0, 0, MS_OPT_MIN, NULL},
        {NULL, 0, 0, 0, 0, 0, NULL}};
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "rawtimestep");
    raw_args a = {NULL, 0};
    if (!m || ms_args_options(interp, objc, objv, 3, options, &a, NULL)) return TCL_ERROR;
    long f = (long)m->nframes - 1;   /* the last frame, or -1: a new one */
    if (a.frame && frame_word(interp, m, a.frame, 1, &f)) return TCL_ERROR;
    int len;
    const unsigned char *bytes = Tcl_GetByteArrayFromObj(objv[2], &len);
    size_t n = (size_t)len / (3 * sizeof(float));
    if ((size_t)len % (3 * sizeof(float)) || n == 0 || (size_t)a.start > m->atoms.n ||
        n > m->atoms.n - (size_t)a.start)
        return ms_cmd_error(interp, "rawtimestep: %d bytes from atom %ld: molecule %d has %zu "
                            "atoms, 12 bytes (x y z as 32-bit floats) each", len, a.start,
                            m->id, m->atoms.n);
    ms_error err = {{0}};
    ms_frame *fr = f >= 0 ? ms_mol_frame_pin(m, (size_t)f, &err) : new_frame(m, &err);
    if (!fr) return ms_cmd_error(interp, "rawtimestep: %s", err.msg);
    memcpy(fr->pos + 3 * a.start, bytes, n * 3 * sizeof(float));
    if (f < 0) {
        ms_cmd_frames_appended(app, m);
    } else {
        ms_molset_emit(&app->mols, MS_EV_FRAME, m, NULL);
    }
    return TCL_OK;
}

void ms_cmd_timestep_register(ms_app *app)
{
    static const ms_subcmd cmds[] = {
        {"gettimestep", gettimestep, 2, 2, "<molid> <frame>"},
        {"rawtimestep", rawtimestep, 2, 6,
         "<molid> <bytes> ?-frame current|last|new|<n>? ?-start <index>?"}};
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
