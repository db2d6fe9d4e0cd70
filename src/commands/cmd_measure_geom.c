/* cmd_measure_geom.c: the `measure` subcommands that take atoms by index rather than by
 * selection, and the matrix inverse:
 *
 *   measure bond  {{i ?molid?} {j ?molid?}}             -> distances
 *   measure angle {{i ?m?} {j ?m?} {k ?m?}}             -> angles at j, degrees
 *   measure dihed|imprp {{i ?m?} {j ?m?} {k ?m?} {l ?m?}} -> dihedral angles, -180..180
 *         ... ?molid <default molid>? ?frame <f|all|last>? | ?first <f>? ?last <l>?
 *   measure inverse <4x4 matrix>
 *
 * As in VMD, atoms without a molid belong to the default molecule (top unless given); the
 * frames walked are the default molecule's (the current one unless asked otherwise), and
 * atoms of other molecules are read at their molecule's current frame. The answer is a list
 * with one value per frame. Nothing is changed. */
#include "config.h"
#include "commands/commands.h"
#include "commands/tclvec.h"
#include "vecmath/vecmath.h"

#include <limits.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define SUBCMD(name) static int name(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])

typedef struct geom_atom {
    ms_molecule *mol;
    long index;
} geom_atom;

typedef struct geom_args {
    Tcl_Obj *molid;           /* default molecule word, NULL = top */
    Tcl_Obj *frame_word;      /* f, all or last; NULL when not given */
    long frame;               /* -1 none given, -2 last, -3 all */
    long first, last;         /* -1 when not given */
} geom_args;

static const ms_opt geom_options_table[] = {
    {"molid", MS_OPT_OBJ, offsetof(geom_args, molid), 0, 0, 0, NULL},
    {"frame", MS_OPT_OBJ, offsetof(geom_args, frame_word), 0, 0, 0, NULL},
    {"first", MS_OPT_LONG, offsetof(geom_args, first), 0, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"last", MS_OPT_LONG, offsetof(geom_args, last), 0, INT_MAX, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

static int geom_options(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                        geom_args *g)
{
    *g = (geom_args){NULL, NULL, -1, -1, -1};
    if (ms_args_options(interp, objc, objv, 3, geom_options_table, g, NULL)) return TCL_ERROR;
    static const char *const words[] = {"all", "last", NULL};
    int k;
    if (g->frame_word) {
        if (ms_arg_long_or(interp, g->frame_word, "frame", words, 0, INT_MAX, &k, &g->frame))
            return TCL_ERROR;
        if (k >= 0) g->frame = k == 0 ? -3 : -2;
    }
    if (g->frame != -1 && (g->first >= 0 || g->last >= 0))
        return ms_cmd_error(interp, "%s: cannot give a frame and a frame range (first or last) "
                            "together", cmd);
    return TCL_OK;
}

/* The atom list: n entries {index ?molid?}; a repeated neighbour is refused as in VMD. */
static int geom_atoms(ms_app *app, Tcl_Interp *interp, Tcl_Obj *list, int n, ms_molecule *def,
                      const char *cmd, geom_atom *at)
{
    Tcl_Obj **e, **f;
    int ne, nf;
    if (Tcl_ListObjGetElements(NULL, list, &ne, &e) != TCL_OK || ne != n)
        return ms_cmd_error(interp, "%s: expected a list of %d atoms {{index ?molid?} ...}, got "
                            "'%s'", cmd, n, Tcl_GetString(list));
    for (int k = 0; k < n; k++) {
        Tcl_WideInt idx;
        if (Tcl_ListObjGetElements(NULL, e[k], &nf, &f) != TCL_OK || nf < 1 || nf > 2 ||
            Tcl_GetWideIntFromObj(NULL, f[0], &idx) != TCL_OK)
            return ms_cmd_error(interp, "%s: bad atom '%s': expected {index ?molid?}", cmd,
                                Tcl_GetString(e[k]));
        at[k].mol = nf == 2 ? ms_cmd_mol(app, interp, f[1], cmd) : def;
        if (!at[k].mol) return TCL_ERROR;
        if (idx < 0 || (size_t)idx >= at[k].mol->atoms.n)
            return ms_cmd_error(interp, "%s: invalid atom id %lld (molecule %d has %zu atoms)",
                                cmd, (long long)idx, at[k].mol->id, at[k].mol->atoms.n);
        at[k].index = (long)idx;
        if (k > 0 && at[k].mol == at[k - 1].mol && at[k].index == at[k - 1].index)
            return ms_cmd_error(interp, "%s: atom %ld appears twice in a row", cmd, at[k].index);
    }
    return TCL_OK;
}

/* VMD's choice of frames of the default molecule: the current one by default, a single
 * frame (clamped to the last), all of them, or first..last. */
static int geom_frames(Tcl_Interp *interp, const ms_molecule *m, const geom_args *g,
                       const char *cmd, long *first, long *last)
{
    long max = (long)m->nframes - 1, f = g->frame;
    if (m->frame < 0) return ms_cmd_error(interp, "%s: molecule %d has no frames", cmd, m->id);
    if (f == -2 || f > max) f = max;
    if (f >= 0) {
        *first = *last = f;
        return TCL_OK;
    }
    *first = f == -3 ? 0 : g->first, *last = g->last;
    if (*first < 0 && *last < 0) *first = *last = m->frame;
    if (*last < 0 || *last > max) *last = max;
    if (*first < 0) *first = 0;
    return TCL_OK;
}

/* Coordinates of an atom: frame f of the default molecule, else its molecule's current. */
static int atom_pos(Tcl_Interp *interp, const geom_atom *a, const ms_molecule *def, long f,
                    const char *cmd, double p[3])
{
    const ms_molecule *m = a->mol;
    long frame = m == def ? f : m->frame;
    if (frame < 0 || (size_t)frame >= m->nframes)
        return ms_cmd_error(interp, "%s: molecule %d has no frames", cmd, m->id);
    ms_error err = {{0}};
    const float *x = ms_mol_frame_pos(m, (size_t)frame, &err);
    if (!x) return ms_cmd_error(interp, "%s: %s", cmd, err.msg);
    x += 3 * (size_t)a->index;
    p[0] = x[0], p[1] = x[1], p[2] = x[2];
    return TCL_OK;
}

static double geom_value(int n, double p[4][3])
{
    double d[3], e[3];
    if (n == 2) {
        ms_v3_sub(p[1], p[0], d);
        return ms_v3_length(d);
    }
    if (n == 3) {
        ms_v3_sub(p[0], p[1], d);
        ms_v3_sub(p[2], p[1], e);
        return ms_v3_angle(d, e);
    }
    return ms_v3_dihedral(p[0], p[1], p[2], p[3]);
}

static int geom_cmd(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int n,
                    const char *cmd)
{
    geom_args g;
    geom_atom at[4];
    double p[4][3];
    long first = 0, last = -1;
    if (geom_options(interp, objc, objv, cmd, &g) != TCL_OK) return TCL_ERROR;
    Tcl_Obj *word = g.molid ? g.molid : Tcl_NewStringObj("top", -1);
    Tcl_IncrRefCount(word);
    ms_molecule *def = ms_cmd_mol(app, interp, word, cmd);
    Tcl_DecrRefCount(word);
    if (!def || geom_atoms(app, interp, objv[2], n, def, cmd, at) != TCL_OK ||
        geom_frames(interp, def, &g, cmd, &first, &last) != TCL_OK)
        return TCL_ERROR;
    Tcl_Obj *res = Tcl_NewListObj(0, NULL);
    for (long f = first; f <= last; f++) {
        for (int k = 0; k < n; k++)
            if (atom_pos(interp, &at[k], def, f, cmd, p[k]) != TCL_OK) {
                Tcl_DecrRefCount(res);
                return TCL_ERROR;
            }
        Tcl_ListObjAppendElement(NULL, res, Tcl_NewDoubleObj(geom_value(n, p)));
    }
    Tcl_SetObjResult(interp, res);
    return TCL_OK;
}

SUBCMD(m_bond) { return geom_cmd(app, interp, objc, objv, 2, "measure bond"); }
SUBCMD(m_angle) { return geom_cmd(app, interp, objc, objv, 3, "measure angle"); }
SUBCMD(m_dihed) { return geom_cmd(app, interp, objc, objv, 4, "measure dihed"); }
SUBCMD(m_imprp) { return geom_cmd(app, interp, objc, objv, 4, "measure imprp"); }

SUBCMD(m_inverse)
{
    double m[16], inv[16];
    if (ms_tcl_get_mat4(interp, objv[2], "measure inverse", m) != TCL_OK) return TCL_ERROR;
    if (ms_mat4d_inverse(m, inv))
        return ms_cmd_error(interp, "measure inverse: singular matrix, inverse not computed");
    Tcl_SetObjResult(interp, ms_tcl_new_mat4(inv));
    return TCL_OK;
}

void ms_cmd_measure_geom_register(ms_app *app)
{
#define GEOM_USAGE \
    "{{<atomid> ?<molid>?} ...} ?molid <id>? ?frame <f|all|last>? | ?first <f>? ?last <l>?"
    static const ms_subcmd table[] = {
        {"bond", m_bond, 1, MS_ARGS_ANY, GEOM_USAGE},
        {"angle", m_angle, 1, MS_ARGS_ANY, GEOM_USAGE},
        {"dihed", m_dihed, 1, MS_ARGS_ANY, GEOM_USAGE},
        {"imprp", m_imprp, 1, MS_ARGS_ANY, GEOM_USAGE},
        {"inverse", m_inverse, 1, 1, "<matrix>"},
        {NULL, NULL, 0, 0, NULL}};
    ms_cmdset_extend(app, "measure", table);
}
