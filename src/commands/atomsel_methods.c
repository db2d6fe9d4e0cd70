/* atomsel_methods.c: the methods of a selection object other than get/set:
 *
 *   num, list, molid|molindex, text, type, frame ?f?, update, delete, global, uplevel L,
 *   getbonds, setbonds, getbondorders, setbondorders, getbondtypes, setbondtypes,
 *   moveby {v}, moveto {v}, lmoveby {vs}, lmoveto {vs}, move {4x4}, write<type> file
 *
 * Coordinates change on the selection's frame; changes are announced to listeners
 * (MS_EV_FRAME for coordinates, MS_EV_STRUCTURE for bonds). */
#include "config.h"
#include "commands/atomsel_int.h"
#include "commands/commands.h"
#include "fileio/write.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- simple queries */

static int m_num(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    if (!ms_atomsel_fresh(app, interp, s, "num")) return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewWideIntObj((Tcl_WideInt)s->count));
    return TCL_OK;
}

static int m_list(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    if (!ms_atomsel_fresh(app, interp, s, "list")) return TCL_ERROR;
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < s->count; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewWideIntObj(s->indices[i]));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

static int m_molid(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(s->molid));
    return TCL_OK;
}

static int m_text(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_sel_text(s->expr), -1));
    return TCL_OK;
}

static int m_type(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewStringObj("atomselect", -1));
    return TCL_OK;
}

/* frame: now, last or the number; frame f sets it (the selection is not re-evaluated until
 * `update`, as in VMD). */
static int m_frame(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    if (objc == 3) return ms_atomsel_parse_frame(interp, objv[2], &s->frame);
    if (s->frame == MS_ATOMSEL_NOW) Tcl_SetObjResult(interp, Tcl_NewStringObj("now", -1));
    else if (s->frame == MS_ATOMSEL_LAST) Tcl_SetObjResult(interp, Tcl_NewStringObj("last", -1));
    else Tcl_SetObjResult(interp, Tcl_NewWideIntObj(s->frame));
    return TCL_OK;
}

static int m_update(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    ms_error err = {{0}};
    if (ms_atomsel_update(app, s, &err)) return ms_atomsel_error(interp, s, "update", "%s", err.msg);
    return TCL_OK;
}

/* ---------------------------------------------------------------- lifetime */

static int m_delete(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    char name[sizeof s->name], var[sizeof s->name + 16];
    snprintf(name, sizeof name, "%s", s->name);   /* s is freed when the command goes */
    snprintf(var, sizeof var, "upproc_var_%s", name);
    Tcl_UnsetVar(interp, var, 0);                  /* its trace deletes the command */
    Tcl_CmdInfo info;
    if (Tcl_GetCommandInfo(interp, name, &info)) Tcl_DeleteCommand(interp, name);
    Tcl_ResetResult(interp);
    return TCL_OK;
}

static int m_global(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *level = Tcl_NewStringObj("#0", -1);
    Tcl_IncrRefCount(level);
    int rc = ms_atomsel_retie(interp, level, s->name);
    Tcl_DecrRefCount(level);
    return rc;
}

static int m_uplevel(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    return ms_atomsel_retie(interp, objv[2], s->name);
}

/* ---------------------------------------------------------------- bonds */

/* Per selected atom, a list of its bond partners, orders or types. */
static int bond_lists(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, const char *method,
                      int what)
{
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, method);
    if (!m) return TCL_ERROR;
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    for (size_t q = 0; q < s->count; q++) {
        uint32_t i = s->indices[q];
        Tcl_Obj *l = Tcl_NewListObj(0, NULL);
        for (uint32_t k = m->has_bonds ? m->bonds.start[i] : 0;
             m->has_bonds && k < m->bonds.start[i + 1]; k++) {
            Tcl_Obj *v = what == 0 ? Tcl_NewWideIntObj(m->bonds.to[k])
                       : what == 1 ? Tcl_NewDoubleObj(m->bonds.order ? m->bonds.order[k] : 1.0)
                       : Tcl_NewStringObj(m->bonds.type ? ms_mol_str(m, m->bonds.type[k])
                                                        : "unknown", -1);
            Tcl_ListObjAppendElement(NULL, l, v);
        }
        Tcl_ListObjAppendElement(NULL, out, l);
    }
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

static int m_getbonds(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    return bond_lists(app, interp, s, "getbonds", 0);
}

static int m_getbondorders(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                           Tcl_Obj *const objv[])
{
    return bond_lists(app, interp, s, "getbondorders", 1);
}

static int m_getbondtypes(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                          Tcl_Obj *const objv[])
{
    return bond_lists(app, interp, s, "getbondtypes", 2);
}

/* The order of bond i-j before the change, 1 when there was none. */
static float old_order(const ms_molecule *m, uint32_t i, uint32_t j)
{
    if (!m->has_bonds || !m->bonds.order) return 1.0f;
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
        if (m->bonds.to[k] == j) return m->bonds.order[k];
    return 1.0f;
}

typedef struct pairs {
    uint32_t *ij;
    float *order;
    size_t n, cap, ocap;
} pairs;

static int add_pair(pairs *p, const ms_molecule *m, uint32_t i, uint32_t j)
{
    if (ms_grow((void **)&p->ij, &p->cap, 2 * (p->n + 1), sizeof *p->ij) ||
        ms_grow((void **)&p->order, &p->ocap, p->n + 1, sizeof *p->order))
        return -1;
    p->ij[2 * p->n] = i;
    p->ij[2 * p->n + 1] = j;
    p->order[p->n++] = old_order(m, i, j);
    return 0;
}

/* setbonds: the bonds of the selected atoms become exactly the lists given (bonds between
 * two unselected atoms stay). */
static int m_setbonds(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, "setbonds");
    if (!m) return TCL_ERROR;
    Tcl_Obj **lists;
    int nl;
    if (Tcl_ListObjGetElements(NULL, objv[2], &nl, &lists) != TCL_OK || (size_t)nl != s->count)
        return ms_atomsel_error(interp, s, "setbonds", "expected %zu bond lists, one per selected "
                                "atom, got '%.100s'", s->count, Tcl_GetString(objv[2]));
    pairs p = {0};
    int rc = TCL_OK;
    for (size_t i = 0; m->has_bonds && i < m->atoms.n && rc == TCL_OK; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            uint32_t j = m->bonds.to[k];
            if (j > i && !ms_bitset_get(&s->bits, i) && !ms_bitset_get(&s->bits, j) &&
                add_pair(&p, m, (uint32_t)i, j))
                rc = ms_atomsel_error(interp, s, "setbonds", "out of memory");
        }
    for (int q = 0; q < nl && rc == TCL_OK; q++) {
        Tcl_Obj **to;
        int nt;
        if (Tcl_ListObjGetElements(NULL, lists[q], &nt, &to) != TCL_OK) nt = -1;
        for (int t = 0; t < nt && rc == TCL_OK; t++) {
            Tcl_WideInt j;
            if (Tcl_GetWideIntFromObj(NULL, to[t], &j) != TCL_OK || j < 0 || (size_t)j >= m->atoms.n)
                nt = -1;
            else if (add_pair(&p, m, s->indices[q], (uint32_t)j))
                rc = ms_atomsel_error(interp, s, "setbonds", "out of memory");
        }
        if (nt < 0)
            rc = ms_atomsel_error(interp, s, "setbonds", "bad bond list '%.100s' for atom %u "
                                  "(atom indices from 0 to %zu)", Tcl_GetString(lists[q]),
                                  s->indices[q], m->atoms.n ? m->atoms.n - 1 : 0);
    }
    ms_error err = {{0}};
    if (rc == TCL_OK && ms_mol_set_bonds(m, p.n, p.ij, p.order, &err))
        rc = ms_atomsel_error(interp, s, "setbonds", "%s", err.msg);
    free(p.ij);
    free(p.order);
    if (rc == TCL_OK) ms_molset_emit(&app->mols, MS_EV_STRUCTURE, m, NULL);
    return rc;
}

/* Position of bond i-j in the table, or -1. */
static long bond_slot(const ms_molecule *m, uint32_t i, uint32_t j)
{
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
        if (m->bonds.to[k] == j) return k;
    return -1;
}

/* Check setbondorders/setbondtypes lists: one per selected atom, no more values than the
 * atom has bonds, numbers for orders. */
static int check_bond_values(Tcl_Interp *interp, ms_atomsel *s, const ms_molecule *m,
                             Tcl_Obj **lists, int nl, const char *method, int types)
{
    if ((size_t)nl != s->count)
        return ms_atomsel_error(interp, s, method, "expected %zu lists, one per selected atom",
                                s->count);
    for (int q = 0; q < nl; q++) {
        Tcl_Obj **v;
        int nv;
        uint32_t i = s->indices[q];
        uint32_t have = m->has_bonds ? m->bonds.start[i + 1] - m->bonds.start[i] : 0;
        if (Tcl_ListObjGetElements(NULL, lists[q], &nv, &v) != TCL_OK || (uint32_t)nv > have)
            return ms_atomsel_error(interp, s, method, "atom %u has %u bonds, got '%.100s'", i,
                                    have, Tcl_GetString(lists[q]));
        for (int t = 0; !types && t < nv; t++) {
            double d;
            if (Tcl_GetDoubleFromObj(NULL, v[t], &d) != TCL_OK)
                return ms_atomsel_error(interp, s, method, "bad bond order '%s'",
                                        Tcl_GetString(v[t]));
        }
    }
    return TCL_OK;
}

/* The per-bond order or type array, made (all 1, all "unknown") on first use. */
static int bond_values_array(ms_molecule *m, int types)
{
    size_t nb = m->has_bonds ? m->bonds.start[m->atoms.n] : 0;
    if (!nb || (types ? m->bonds.type != NULL : m->bonds.order != NULL)) return 0;
    if (!types) {
        if (!(m->bonds.order = ms_alloc_array(nb, sizeof *m->bonds.order))) return -1;
        for (size_t k = 0; k < nb; k++) m->bonds.order[k] = 1.0f;
        return 0;
    }
    ms_str unknown = ms_strtab_intern_cstr(m->strings, "unknown");
    if (unknown == MS_STR_NONE || !(m->bonds.type = ms_alloc_array(nb, sizeof *m->bonds.type)))
        return -1;
    for (size_t k = 0; k < nb; k++) m->bonds.type[k] = unknown;
    return 0;
}

/* setbondorders / setbondtypes: per selected atom, values for its first bonds (both
 * directions of each bond change). Everything is checked before anything changes. */
static int set_bond_values(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, Tcl_Obj *arg,
                           const char *method, int types)
{
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, method);
    if (!m) return TCL_ERROR;
    Tcl_Obj **lists;
    int nl;
    if (Tcl_ListObjGetElements(NULL, arg, &nl, &lists) != TCL_OK) nl = -1;
    if (check_bond_values(interp, s, m, lists, nl, method, types)) return TCL_ERROR;
    if (bond_values_array(m, types)) return ms_atomsel_error(interp, s, method, "out of memory");
    for (int q = 0; q < nl; q++) {
        Tcl_Obj **v;
        int nv;
        uint32_t i = s->indices[q];
        Tcl_ListObjGetElements(NULL, lists[q], &nv, &v);
        for (int t = 0; t < nv; t++) {
            uint32_t k = m->bonds.start[i] + (uint32_t)t;
            long back = bond_slot(m, m->bonds.to[k], i);
            if (types) {
                ms_str id = ms_strtab_intern_cstr(m->strings, Tcl_GetString(v[t]));
                if (id == MS_STR_NONE) return ms_atomsel_error(interp, s, method, "out of memory");
                m->bonds.type[k] = id;
                if (back >= 0) m->bonds.type[back] = id;
            } else {
                double d;
                Tcl_GetDoubleFromObj(NULL, v[t], &d);
                m->bonds.order[k] = (float)d;
                if (back >= 0) m->bonds.order[back] = (float)d;
            }
        }
    }
    ms_molset_emit(&app->mols, MS_EV_STRUCTURE, m, NULL);
    return TCL_OK;
}

static int m_setbondorders(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                           Tcl_Obj *const objv[])
{
    return set_bond_values(app, interp, s, objv[2], "setbondorders", 0);
}

static int m_setbondtypes(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                          Tcl_Obj *const objv[])
{
    return set_bond_values(app, interp, s, objv[2], "setbondtypes", 1);
}

/* ---------------------------------------------------------------- moving atoms */

static int get_vec3(Tcl_Interp *interp, ms_atomsel *s, const char *method, Tcl_Obj *o,
                    double v[3])
{
    Tcl_Obj **e;
    int n;
    if (Tcl_ListObjGetElements(NULL, o, &n, &e) == TCL_OK && n == 3 &&
        Tcl_GetDoubleFromObj(NULL, e[0], &v[0]) == TCL_OK &&
        Tcl_GetDoubleFromObj(NULL, e[1], &v[1]) == TCL_OK &&
        Tcl_GetDoubleFromObj(NULL, e[2], &v[2]) == TCL_OK)
        return TCL_OK;
    return ms_atomsel_error(interp, s, method, "expected a vector {x y z}, got '%.100s'",
                            Tcl_GetString(o));
}

/* The coordinates of the selection's frame, or NULL with an error. */
static float *frame_pos(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, const char *method,
                        ms_molecule **mol)
{
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, method);
    if (!m) return NULL;
    long f = ms_sel_resolve_frame(m, s->frame);
    if (f < 0) {
        ms_atomsel_error(interp, s, method, "molecule %d has no coordinates", m->id);
        return NULL;
    }
    ms_error err = {{0}};
    ms_frame *fr = ms_mol_frame_pin(m, (size_t)f, &err);   /* moved: the frame stays */
    if (!fr) {
        ms_atomsel_error(interp, s, method, "%s", err.msg);
        return NULL;
    }
    *mol = m;
    return fr->pos;
}

/* moveby / moveto {x y z}; lmoveby / lmoveto {{x y z} ...}, one vector per atom. */
static int move_common(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, Tcl_Obj *arg,
                       const char *method, int per_atom, int add)
{
    ms_molecule *m;
    float *pos = frame_pos(app, interp, s, method, &m);
    if (!pos) return TCL_ERROR;
    Tcl_Obj **vs = &arg;
    int nv = 1;
    if (per_atom && (Tcl_ListObjGetElements(NULL, arg, &nv, &vs) != TCL_OK || (size_t)nv != s->count))
        return ms_atomsel_error(interp, s, method, "expected %zu vectors, one per selected atom",
                                s->count);
    double *v = ms_alloc_array((size_t)nv * 3, sizeof *v);
    if (!v) return ms_atomsel_error(interp, s, method, "out of memory");
    for (int q = 0; q < nv; q++)
        if (get_vec3(interp, s, method, vs[q], v + 3 * q)) {
            free(v);
            return TCL_ERROR;
        }
    for (size_t q = 0; q < s->count; q++) {
        float *p = pos + 3 * (size_t)s->indices[q];
        const double *d = v + (per_atom ? 3 * q : 0);
        for (int k = 0; k < 3; k++) p[k] = add ? (float)(p[k] + d[k]) : (float)d[k];
    }
    free(v);
    ms_molset_emit(&app->mols, MS_EV_FRAME, m, NULL);
    return TCL_OK;
}

static int m_moveby(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    return move_common(app, interp, s, objv[2], "moveby", 0, 1);
}

static int m_moveto(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    return move_common(app, interp, s, objv[2], "moveto", 0, 0);
}

static int m_lmoveby(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    return move_common(app, interp, s, objv[2], "lmoveby", 1, 1);
}

static int m_lmoveto(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    return move_common(app, interp, s, objv[2], "lmoveto", 1, 0);
}

/* move {{r0} {r1} {r2} {r3}}: p' = M p, rows as written (VMD's `trans` matrices). */
static int m_move(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    double M[16];
    Tcl_Obj **rows, **cols;
    int nr, nc, ok = Tcl_ListObjGetElements(NULL, objv[2], &nr, &rows) == TCL_OK;
    if (ok && nr == 1) ok = Tcl_ListObjGetElements(NULL, rows[0], &nr, &rows) == TCL_OK;
    ok = ok && nr == 4;
    for (int r = 0; ok && r < 4; r++) {
        ok = Tcl_ListObjGetElements(NULL, rows[r], &nc, &cols) == TCL_OK && nc == 4;
        for (int c = 0; ok && c < 4; c++)
            ok = Tcl_GetDoubleFromObj(NULL, cols[c], &M[4 * r + c]) == TCL_OK;
    }
    if (!ok)
        return ms_atomsel_error(interp, s, "move", "expected a 4x4 matrix {{r0} {r1} {r2} {r3}}, "
                                "got '%.100s'", Tcl_GetString(objv[2]));
    ms_molecule *m;
    float *pos = frame_pos(app, interp, s, "move", &m);
    if (!pos) return TCL_ERROR;
    for (size_t q = 0; q < s->count; q++) {
        float *p = pos + 3 * (size_t)s->indices[q];
        double x = p[0], y = p[1], z = p[2];
        for (int r = 0; r < 3; r++)
            p[r] = (float)(M[4 * r] * x + M[4 * r + 1] * y + M[4 * r + 2] * z + M[4 * r + 3]);
    }
    ms_molset_emit(&app->mols, MS_EV_FRAME, m, NULL);
    return TCL_OK;
}

/* ---------------------------------------------------------------- writing */

/* write<type> file: the selected atoms of the selection's frame. */
static int m_write(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc, Tcl_Obj *const objv[])
{
    const char *method = Tcl_GetString(objv[1]);
    char type[64];
    snprintf(type, sizeof type, "%s", method + 5);
    for (char *c = type; *c; c++) *c = (char)tolower((unsigned char)*c);
    ms_molecule *m = ms_atomsel_fresh(app, interp, s, method);
    if (!m) return TCL_ERROR;
    long f = ms_sel_resolve_frame(m, s->frame);
    if (f < 0) return ms_atomsel_error(interp, s, method, "molecule %d has no coordinates", m->id);
    ms_write_opts o;
    ms_write_opts_default(&o);
    o.type = type;
    o.atoms = s->indices;
    o.natoms = s->count;
    o.first = o.last = f;
    ms_error err = {{0}};
    const char *path = Tcl_GetString(objv[2]);
    if (ms_write_file(&app->plugins, m, path, &o, &err) < 0)
        return ms_atomsel_error(interp, s, method, "%s: %s", path, err.msg);
    Tcl_ResetResult(interp);
    return TCL_OK;
}

const struct ms_atomsel_method ms_atomsel_methods[] = {
    {"num", m_num, 0, 0, "", 0},
    {"list", m_list, 0, 0, "", 0},
    {"molid", m_molid, 0, 0, "", 0},
    {"molindex", m_molid, 0, 0, "", 0},
    {"text", m_text, 0, 0, "", 0},
    {"type", m_type, 0, 0, "", 0},
    {"frame", m_frame, 0, 1, "?<n|first|last|now>?", 0},
    {"update", m_update, 0, 0, "", 0},
    {"get", ms_atomsel_get, 1, 1, "<keywords>", 0},
    {"set", ms_atomsel_set, 2, 2, "<keywords> <values>", 1},
    {"getbonds", m_getbonds, 0, 0, "", 0},
    {"setbonds", m_setbonds, 1, 1, "<bond lists>", 1},
    {"getbondorders", m_getbondorders, 0, 0, "", 0},
    {"setbondorders", m_setbondorders, 1, 1, "<order lists>", 1},
    {"getbondtypes", m_getbondtypes, 0, 0, "", 0},
    {"setbondtypes", m_setbondtypes, 1, 1, "<type lists>", 1},
    {"moveby", m_moveby, 1, 1, "{x y z}", 1},
    {"moveto", m_moveto, 1, 1, "{x y z}", 1},
    {"lmoveby", m_lmoveby, 1, 1, "{{x y z} ...}", 1},
    {"lmoveto", m_lmoveto, 1, 1, "{{x y z} ...}", 1},
    {"move", m_move, 1, 1, "<4x4 matrix>", 1},
    {"delete", m_delete, 0, 0, "", 0},
    {"global", m_global, 0, 0, "", 0},
    {"uplevel", m_uplevel, 1, 1, "<level>", 0},
    {"write<type>", m_write, 1, 1, "<file>", 0},   /* writepdb, writexyz ... */
    {NULL, NULL, 0, 0, NULL, 0},
};
