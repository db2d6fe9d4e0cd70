/* cmd_topo.c: ::molscope::topo, the C half of the topotools package (tcl/topotools): the
 * per-bond and per-term loops of `topo` over a selection's molecule. Every subcommand takes
 * a selection object first (the Tcl side makes it from -molid and -sel):
 *   numbonds|bondtypenames|clearbonds|retypebonds <sel>
 *   getbondlist <sel> type|order|both|none     setbondlist <sel> <flag> <list>
 *   addbond <sel> <i> <j> <type> <order>       delbond <sel> <i> <j>
 * and the same for angles, dihedrals and impropers (numangles, getanglelist, setanglelist,
 * addangle <sel> <atoms> <type>, delangle <sel> <atoms>, clearangles, angletypenames,
 * retypeangles, guessangles ...; guessimpropers <sel> <tolerance>). A term list is
 * {type i j k ...} per term; an untyped bond or term reads "unknown". Atom guesses and new
 * molecules are in cmd_topo_build.c. */
#include "config.h"
#include "commands/atomsel.h"
#include "commands/commands.h"
#include "commands/topo.h"
#include "molecule/analysis.h"
#include "molecule/combine.h"
#include "molecule/molset.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the selection */

int ms_topo_sel_open(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, ms_topo_sel *t)
{
    memset(t, 0, sizeof *t);
    int molid;
    if (ms_atomsel_resolve(app, interp, Tcl_GetString(word), ms_args_where(), &molid, &t->frame,
                           &t->atoms, &t->n))
        return TCL_ERROR;
    t->m = ms_molset_get(&app->mols, molid);
    if (!(t->in = calloc(t->m->atoms.n + 1, 1))) {
        free(t->atoms);
        return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    }
    for (size_t k = 0; k < t->n; k++) t->in[t->atoms[k]] = 1;
    return TCL_OK;
}

void ms_topo_sel_close(ms_topo_sel *t)
{
    free(t->atoms);
    free(t->in);
}

/* An atom index word, within the molecule. */
static int atom_word(Tcl_Interp *interp, Tcl_Obj *w, const ms_molecule *m, uint32_t *out)
{
    long v;
    if (ms_arg_long(NULL, w, NULL, 0, (long)m->atoms.n - 1, &v) != TCL_OK)
        return ms_cmd_error(interp, "%s: bad atom index '%s': must be 0 to %ld", ms_args_where(),
                            Tcl_GetString(w), (long)m->atoms.n - 1);
    *out = (uint32_t)v;
    return TCL_OK;
}

static const char *type_text(const ms_molecule *m, ms_str s)
{
    const char *t = s == MS_STR_NONE ? "" : ms_mol_str(m, s);
    return *t ? t : "unknown";
}

/* A type word: "" or "unknown" is no type. */
static ms_str type_word(ms_molecule *m, const char *w)
{
    if (!*w || !strcmp(w, "unknown")) return ms_strtab_intern_cstr(m->strings, "");
    return ms_strtab_intern_cstr(m->strings, w);
}

/* ---------------------------------------------------------------- bonds */

/* Every bond (i < j) of the molecule as pairs, with order and type; keep() decides. */
typedef struct bond_list {
    uint32_t *ij;
    float *order;
    ms_str *type;
    size_t n, cap, ocap, tcap;
} bond_list;

static int bl_add(bond_list *b, uint32_t i, uint32_t j, float order, ms_str type)
{
    if (ms_grow((void **)&b->ij, &b->cap, 2 * (b->n + 1), sizeof *b->ij) ||
        ms_grow((void **)&b->order, &b->ocap, b->n + 1, sizeof *b->order) ||
        ms_grow((void **)&b->type, &b->tcap, b->n + 1, sizeof *b->type))
        return -1;
    b->ij[2 * b->n] = i, b->ij[2 * b->n + 1] = j;
    b->order[b->n] = order, b->type[b->n++] = type;
    return 0;
}

static void bl_free(bond_list *b) { free(b->ij), free(b->order), free(b->type); }

/* The molecule's bonds, less those with both atoms in the selection when drop_inside, less
 * the bond a-b when a != b. */
static int bl_current(const ms_topo_sel *t, int drop_inside, uint32_t a, uint32_t b,
                      bond_list *out)
{
    const ms_molecule *m = t->m;
    for (uint32_t i = 0; m->has_bonds && i < m->atoms.n; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            uint32_t j = m->bonds.to[k];
            if (j <= i || (drop_inside && t->in[i] && t->in[j])) continue;
            if (a != b && ((i == a && j == b) || (i == b && j == a))) continue;
            if (bl_add(out, i, j, m->bonds.order ? m->bonds.order[k] : 1.0f,
                       m->bonds.type ? m->bonds.type[k] : MS_STR_NONE))
                return -1;
        }
    return 0;
}

/* Make the molecule's bonds exactly these (with their orders and types) and tell. */
static int bl_apply(ms_app *app, Tcl_Interp *interp, ms_molecule *m, bond_list *b)
{
    ms_error err = {{0}};
    int typed = 0;
    for (size_t k = 0; k < b->n; k++) typed |= b->type[k] != MS_STR_NONE;
    if (ms_mol_set_bonds(m, b->n, b->ij, b->order, &err) ||
        (typed && ms_bonds_set_types(m, b->ij, b->type, b->n, &err)))
        return ms_cmd_error(interp, "%s: %s", ms_args_where(), err.msg);
    ms_molset_emit(&app->mols, MS_EV_STRUCTURE, m, NULL);
    return TCL_OK;
}

static int numbonds(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    bond_list b = {0};
    int rc = bl_current(&t, 0, 0, 0, &b);
    long n = 0;
    for (size_t k = 0; k < b.n; k++) n += t.in[b.ij[2 * k]] && t.in[b.ij[2 * k + 1]];
    ms_topo_sel_close(&t);
    bl_free(&b);
    if (rc) return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    Tcl_SetObjResult(interp, Tcl_NewLongObj(n));
    return TCL_OK;
}

static const char *const bond_flags[] = {"type", "order", "both", "none", NULL};
enum { BF_TYPE, BF_ORDER, BF_BOTH, BF_NONE };

static Tcl_Obj *bond_obj(const ms_molecule *m, const bond_list *b, size_t k, int flag)
{
    Tcl_Obj *e = Tcl_NewListObj(0, NULL);
    Tcl_ListObjAppendElement(NULL, e, Tcl_NewLongObj(b->ij[2 * k]));
    Tcl_ListObjAppendElement(NULL, e, Tcl_NewLongObj(b->ij[2 * k + 1]));
    if (flag == BF_TYPE || flag == BF_BOTH)
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewStringObj(type_text(m, b->type[k]), -1));
    if (flag == BF_ORDER || flag == BF_BOTH)
        Tcl_ListObjAppendElement(NULL, e, Tcl_NewDoubleObj(b->order[k]));
    return e;
}

static int getbondlist(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int flag = BF_NONE;
    if (objc > 3 && ms_arg_choice(interp, objv[3], bond_flags, "flag", &flag)) return TCL_ERROR;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    bond_list b = {0};
    int rc = bl_current(&t, 0, 0, 0, &b);
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    for (size_t k = 0; !rc && k < b.n; k++)
        if (t.in[b.ij[2 * k]] && t.in[b.ij[2 * k + 1]])
            Tcl_ListObjAppendElement(NULL, out, bond_obj(t.m, &b, k, flag));
    ms_topo_sel_close(&t);
    bl_free(&b);
    if (rc) {
        Tcl_DecrRefCount(Tcl_NewListObj(0, NULL));
        return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    }
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

/* One element of a setbondlist list: {i j [type] [order]} as the flag says. */
static int parse_bond(Tcl_Interp *interp, ms_molecule *m, Tcl_Obj *e, int flag, bond_list *b)
{
    Tcl_Obj **v;
    int nv, want = flag == BF_BOTH ? 4 : flag == BF_NONE ? 2 : 3;
    uint32_t i, j;
    double order = 1.0;
    ms_str type = MS_STR_NONE;
    if (Tcl_ListObjGetElements(NULL, e, &nv, &v) != TCL_OK || nv != want)
        return ms_cmd_error(interp, "%s: bad bond '%.80s': expected %d elements", ms_args_where(),
                            Tcl_GetString(e), want);
    if (atom_word(interp, v[0], m, &i) || atom_word(interp, v[1], m, &j)) return TCL_ERROR;
    if (flag == BF_TYPE || flag == BF_BOTH) type = type_word(m, Tcl_GetString(v[2]));
    if ((flag == BF_ORDER || flag == BF_BOTH) &&
        ms_arg_double(interp, v[nv - 1], "bond order", &order))
        return TCL_ERROR;
    if (bl_add(b, i, j, (float)order, type))
        return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    return TCL_OK;
}

static int setbondlist(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int flag;
    Tcl_Obj **el;
    int ne;
    if (ms_arg_choice(interp, objv[3], bond_flags, "flag", &flag)) return TCL_ERROR;
    if (Tcl_ListObjGetElements(interp, objv[4], &ne, &el) != TCL_OK) return TCL_ERROR;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    bond_list b = {0};
    int rc = bl_current(&t, 1, 0, 0, &b) ? ms_cmd_error(interp, "%s: out of memory",
                                                        ms_args_where())
                                         : TCL_OK;
    for (int k = 0; k < ne && rc == TCL_OK; k++) rc = parse_bond(interp, t.m, el[k], flag, &b);
    if (rc == TCL_OK) rc = bl_apply(app, interp, t.m, &b);
    ms_topo_sel_close(&t);
    bl_free(&b);
    return rc;
}

/* addbond <sel> i j type order, delbond <sel> i j, clearbonds <sel>. */
static int editbond(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *what = Tcl_GetString(objv[1]);
    int add = ms_word_eq(what, "addbond"), clear = ms_word_eq(what, "clearbonds");
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    uint32_t i = 0, j = 0;
    double order = 1.0;
    int rc = TCL_OK;
    if (!clear && (atom_word(interp, objv[3], t.m, &i) || atom_word(interp, objv[4], t.m, &j)))
        rc = TCL_ERROR;
    if (rc == TCL_OK && add && objc > 6 && ms_arg_double(interp, objv[6], "bond order", &order))
        rc = TCL_ERROR;
    if (rc == TCL_OK && !clear && i == j)
        rc = ms_cmd_error(interp, "%s: an atom cannot bond to itself", ms_args_where());
    bond_list b = {0};
    if (rc == TCL_OK && bl_current(&t, clear, i, clear ? i : j, &b))
        rc = ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    if (rc == TCL_OK && add &&
        bl_add(&b, i, j, (float)order, type_word(t.m, objc > 5 ? Tcl_GetString(objv[5]) : "")))
        rc = ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    if (rc == TCL_OK) rc = bl_apply(app, interp, t.m, &b);
    ms_topo_sel_close(&t);
    bl_free(&b);
    return rc;
}

/* Atom types of a bond or term joined by '-', ends ordered so that a term and its
 * reversal read alike (an improper keeps its order). */
void ms_topo_joined_type(const ms_molecule *m, const uint32_t *at, size_t w, int improper,
                        char *out, size_t cap)
{
    const char *ty[4];
    for (size_t q = 0; q < w; q++) ty[q] = ms_mol_str(m, m->atoms.type[at[q]]);
    int rev = 0;
    if (!improper)
        for (size_t q = 0; q < w / 2 && !rev; q++) {
            int c = strcmp(ty[q], ty[w - 1 - q]);
            if (c) {
                rev = c > 0;
                break;
            }
        }
    size_t len = 0;
    out[0] = '\0';
    for (size_t q = 0; q < w; q++) {
        const char *s = ty[rev ? w - 1 - q : q];
        int n = snprintf(out + len, cap - len, "%s%s", q ? "-" : "", s);
        if (n < 0 || (size_t)n >= cap - len) break;
        len += (size_t)n;
    }
}

static int retypebonds(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    bond_list b = {0};
    int rc = bl_current(&t, 0, 0, 0, &b) ? ms_cmd_error(interp, "%s: out of memory",
                                                        ms_args_where())
                                         : TCL_OK;
    for (size_t k = 0; rc == TCL_OK && k < b.n; k++) {
        if (!t.in[b.ij[2 * k]] || !t.in[b.ij[2 * k + 1]]) continue;
        char name[256];
        ms_topo_joined_type(t.m, b.ij + 2 * k, 2, 0, name, sizeof name);
        b.type[k] = ms_strtab_intern_cstr(t.m->strings, name);
    }
    if (rc == TCL_OK) rc = bl_apply(app, interp, t.m, &b);
    ms_topo_sel_close(&t);
    bl_free(&b);
    return rc;
}

/* Sorted unique names (as Tcl's lsort -unique) of the strings given. */
static int set_sorted_names(Tcl_Interp *interp, Tcl_Obj *list)
{
    Tcl_Obj *cmd[3] = {Tcl_NewStringObj("lsort", -1), Tcl_NewStringObj("-unique", -1), list};
    for (int k = 0; k < 3; k++) Tcl_IncrRefCount(cmd[k]);
    int rc = Tcl_EvalObjv(interp, 3, cmd, 0);
    for (int k = 0; k < 3; k++) Tcl_DecrRefCount(cmd[k]);
    return rc;
}

static int bondtypenames(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    bond_list b = {0};
    int rc = bl_current(&t, 0, 0, 0, &b);
    Tcl_Obj *names = Tcl_NewListObj(0, NULL);
    for (size_t k = 0; !rc && k < b.n; k++)
        if (t.in[b.ij[2 * k]] && t.in[b.ij[2 * k + 1]])
            Tcl_ListObjAppendElement(NULL, names, Tcl_NewStringObj(type_text(t.m, b.type[k]), -1));
    ms_topo_sel_close(&t);
    bl_free(&b);
    if (rc) {
        Tcl_DecrRefCount(names);
        return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    }
    return set_sorted_names(interp, names);
}

/* ---------------------------------------------------------------- terms */

/* The kind a subcommand word names (numangles, getdihedrallist ...). */
static int kind_of(Tcl_Obj *word)
{
    const char *w = Tcl_GetString(word);
    return strstr(w, "angle") ? MS_TERM_ANGLE : strstr(w, "dihedral") ? MS_TERM_DIHEDRAL
                                                                      : MS_TERM_IMPROPER;
}

static int term_inside(const ms_topo_sel *t, int kind, size_t k)
{
    size_t w = ms_term_width(kind);
    const uint32_t *at = t->m->terms[kind].atoms + w * k;
    for (size_t q = 0; q < w; q++)
        if (!t->in[at[q]]) return 0;
    return 1;
}

static int numterms(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int kind = kind_of(objv[1]);
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    long n = 0;
    for (size_t k = 0; k < t.m->terms[kind].n; k++) n += term_inside(&t, kind, k);
    ms_topo_sel_close(&t);
    Tcl_SetObjResult(interp, Tcl_NewLongObj(n));
    return TCL_OK;
}

static ms_str term_type(const ms_molecule *m, int kind, size_t k)
{
    return m->terms[kind].type ? m->terms[kind].type[k] : MS_STR_NONE;
}

/* gettermlist: {type a b c ...} per term; termtypenames: the sorted unique types. */
static int listterms(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int kind = kind_of(objv[1]), names = strstr(Tcl_GetString(objv[1]), "typenames") != NULL;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    const ms_terms *tr = &t.m->terms[kind];
    size_t w = ms_term_width(kind);
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    for (size_t k = 0; k < tr->n; k++) {
        if (!term_inside(&t, kind, k)) continue;
        Tcl_Obj *ty = Tcl_NewStringObj(type_text(t.m, term_type(t.m, kind, k)), -1);
        if (names) {
            Tcl_ListObjAppendElement(NULL, out, ty);
            continue;
        }
        Tcl_Obj *e = Tcl_NewListObj(1, &ty);
        for (size_t q = 0; q < w; q++)
            Tcl_ListObjAppendElement(NULL, e, Tcl_NewLongObj(tr->atoms[w * k + q]));
        Tcl_ListObjAppendElement(NULL, out, e);
    }
    ms_topo_sel_close(&t);
    if (names) return set_sorted_names(interp, out);
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

/* Is term k the same atoms as at (or reversed, for angles and dihedrals)? */
static int same_term(const ms_molecule *m, int kind, size_t k, const uint32_t *at)
{
    size_t w = ms_term_width(kind);
    const uint32_t *a = m->terms[kind].atoms + w * k;
    int fwd = 1, rev = kind != MS_TERM_IMPROPER;
    for (size_t q = 0; q < w; q++) {
        fwd &= a[q] == at[q];
        rev &= a[q] == at[w - 1 - q];
    }
    return fwd || rev;
}

/* Drop the terms that are inside the selection (inside) or equal to at (at != NULL). */
static int drop_terms(ms_topo_sel *t, int kind, int inside, const uint32_t *at)
{
    ms_terms *tr = &t->m->terms[kind];
    uint8_t *keep = malloc(tr->n + 1);
    if (!keep) return -1;
    for (size_t k = 0; k < tr->n; k++)
        keep[k] = !((inside && term_inside(t, kind, k)) || (at && same_term(t->m, kind, k, at)));
    ms_terms_keep(tr, kind, keep);
    free(keep);
    return 0;
}

int ms_topo_drop_inside(ms_topo_sel *t, int kind) { return drop_terms(t, kind, 1, NULL); }

/* The atoms of a term from words (width of them). */
static int term_atoms(Tcl_Interp *interp, const ms_molecule *m, int kind, Tcl_Obj *const *w,
                      uint32_t *at)
{
    for (size_t q = 0; q < ms_term_width(kind); q++)
        if (atom_word(interp, w[q], m, &at[q])) return TCL_ERROR;
    for (size_t q = 0; q < ms_term_width(kind); q++)
        for (size_t r = q + 1; r < ms_term_width(kind); r++)
            if (at[q] == at[r])
                return ms_cmd_error(interp, "%s: atom %u appears twice", ms_args_where(), at[q]);
    return TCL_OK;
}

static int add_one(Tcl_Interp *interp, ms_molecule *m, int kind, const uint32_t *at,
                   const char *type)
{
    ms_error err = {{0}};
    ms_str ty = type ? type_word(m, type) : MS_STR_NONE;
    if ((type && ty == MS_STR_NONE) || ms_terms_add(m, kind, at, ty, &err))
        return ms_cmd_error(interp, "%s: %s", ms_args_where(), err.msg[0] ? err.msg : "out of memory");
    return TCL_OK;
}

static int done(ms_app *app, ms_topo_sel *t, int rc)
{
    if (rc == TCL_OK) ms_molset_emit(&app->mols, MS_EV_STRUCTURE, t->m, NULL);
    ms_topo_sel_close(t);
    return rc;
}

/* addangle <sel> <atoms...> <type>, delangle <sel> <atoms...>, clearangles <sel>. */
static int editterm(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int kind = kind_of(objv[1]);
    const char *what = Tcl_GetString(objv[1]);
    int add = !strncmp(what, "add", 3), clear = !strncmp(what, "clear", 5);
    size_t w = ms_term_width(kind);
    if (!clear && (size_t)objc < 3 + w + (size_t)add) return ms_args_usage(interp);
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    uint32_t at[4];
    int rc = clear ? TCL_OK : term_atoms(interp, t.m, kind, objv + 3, at);
    if (rc == TCL_OK && drop_terms(&t, kind, clear, clear ? NULL : at))
        rc = ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    if (rc == TCL_OK && add) rc = add_one(interp, t.m, kind, at, Tcl_GetString(objv[3 + w]));
    return done(app, &t, rc);
}

static int settermlist(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int kind = kind_of(objv[1]);
    size_t w = ms_term_width(kind);
    Tcl_Obj **el;
    int ne;
    if (Tcl_ListObjGetElements(interp, objv[3], &ne, &el) != TCL_OK) return TCL_ERROR;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    int rc = drop_terms(&t, kind, 1, NULL) ? ms_cmd_error(interp, "%s: out of memory",
                                                          ms_args_where())
                                           : TCL_OK;
    for (int k = 0; k < ne && rc == TCL_OK; k++) {
        Tcl_Obj **v;
        int nv;
        uint32_t at[4];
        if (Tcl_ListObjGetElements(NULL, el[k], &nv, &v) != TCL_OK ||
            ((size_t)nv != w + 1 && (size_t)nv != w)) {
            rc = ms_cmd_error(interp, "%s: bad term '%.80s': expected {type atom ...} with %zu "
                              "atoms", ms_args_where(), Tcl_GetString(el[k]), w);
            break;
        }
        int typed = (size_t)nv == w + 1;
        rc = term_atoms(interp, t.m, kind, v + typed, at);
        if (rc == TCL_OK) rc = add_one(interp, t.m, kind, at, typed ? Tcl_GetString(v[0]) : NULL);
    }
    return done(app, &t, rc);
}

/* The type array of a kind's terms, made (every type "") on first use; 0 or -1. */
static int term_types(ms_molecule *m, ms_terms *tr)
{
    if (tr->type) return 0;
    ms_str blank = ms_strtab_intern_cstr(m->strings, "");
    if (blank == MS_STR_NONE || !(tr->type = ms_alloc_array(tr->cap ? tr->cap : 1, sizeof *tr->type)))
        return -1;
    for (size_t k = 0; k < tr->n; k++) tr->type[k] = blank;
    return 0;
}

static int retypeterms(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int kind = kind_of(objv[1]);
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    ms_terms *tr = &t.m->terms[kind];
    size_t w = ms_term_width(kind);
    int rc = tr->n && term_types(t.m, tr) ? ms_cmd_error(interp, "%s: out of memory",
                                                          ms_args_where())
                                          : TCL_OK;
    for (size_t k = 0; k < tr->n && rc == TCL_OK; k++) {
        if (!term_inside(&t, kind, k)) continue;
        char name[256];
        ms_topo_joined_type(t.m, tr->atoms + w * k, w, kind == MS_TERM_IMPROPER, name, sizeof name);
        ms_str ty = ms_strtab_intern_cstr(t.m->strings, name);
        if (ty == MS_STR_NONE) rc = ms_cmd_error(interp, "%s: out of memory", ms_args_where());
        else tr->type[k] = ty;
    }
    return done(app, &t, rc);
}

/* ---------------------------------------------------------------- the table */

static const ms_subcmd topo_table[] = {
    {"numbonds", numbonds, 1, 1, "<sel>"},
    {"getbondlist", getbondlist, 1, 2, "<sel> ?type|order|both|none?"},
    {"setbondlist", setbondlist, 3, 3, "<sel> type|order|both|none <list>"},
    {"addbond", editbond, 3, 5, "<sel> <i> <j> ?<type>? ?<order>?"},
    {"delbond", editbond, 3, 3, "<sel> <i> <j>"},
    {"clearbonds", editbond, 1, 1, "<sel>"},
    {"bondtypenames", bondtypenames, 1, 1, "<sel>"},
    {"retypebonds", retypebonds, 1, 1, "<sel>"},
    {"numangles", numterms, 1, 1, "<sel>"},
    {"getanglelist", listterms, 1, 1, "<sel>"},
    {"setanglelist", settermlist, 2, 2, "<sel> <list>"},
    {"addangle", editterm, 5, 5, "<sel> <i> <j> <k> <type>"},
    {"delangle", editterm, 4, 5, "<sel> <i> <j> <k> ?<type>?"},
    {"clearangles", editterm, 1, 1, "<sel>"},
    {"angletypenames", listterms, 1, 1, "<sel>"},
    {"retypeangles", retypeterms, 1, 1, "<sel>"},
    {"guessangles", ms_topo_guessterms, 1, 2, "<sel> ?<tolerance>?"},
    {"numdihedrals", numterms, 1, 1, "<sel>"},
    {"getdihedrallist", listterms, 1, 1, "<sel>"},
    {"setdihedrallist", settermlist, 2, 2, "<sel> <list>"},
    {"adddihedral", editterm, 6, 6, "<sel> <i> <j> <k> <l> <type>"},
    {"deldihedral", editterm, 5, 6, "<sel> <i> <j> <k> <l> ?<type>?"},
    {"cleardihedrals", editterm, 1, 1, "<sel>"},
    {"dihedraltypenames", listterms, 1, 1, "<sel>"},
    {"retypedihedrals", retypeterms, 1, 1, "<sel>"},
    {"guessdihedrals", ms_topo_guessterms, 1, 2, "<sel> ?<tolerance>?"},
    {"numimpropers", numterms, 1, 1, "<sel>"},
    {"getimproperlist", listterms, 1, 1, "<sel>"},
    {"setimproperlist", settermlist, 2, 2, "<sel> <list>"},
    {"addimproper", editterm, 6, 6, "<sel> <i> <j> <k> <l> <type>"},
    {"delimproper", editterm, 5, 6, "<sel> <i> <j> <k> <l> ?<type>?"},
    {"clearimpropers", editterm, 1, 1, "<sel>"},
    {"impropertypenames", listterms, 1, 1, "<sel>"},
    {"retypeimpropers", retypeterms, 1, 1, "<sel>"},
    {"guessimpropers", ms_topo_guessterms, 1, 2, "<sel> ?<tolerance>?"},
    {"guessatom", ms_topo_guessatom, 3, 3, "<sel> <what> <from>"},
    {"combine", ms_topo_combine, 2, 2, "<selections> <all frames>"},
    {"replicate", ms_topo_replicate, 4, 4, "<sel> <nx> <ny> <nz>"},
    {"readdata", ms_topo_readdata, 2, 2, "<file> <atom style>"},
    {"writedata", ms_topo_writedata, 3, 3, "<sel> <file> <atom style>"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_topo_register(ms_app *app)
{
    ms_cmdset_create(app, "::molscope::topo", topo_table);
}
