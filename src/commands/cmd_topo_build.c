/* cmd_topo_build.c: the subcommands of ::molscope::topo that make things: angles, dihedrals
 * and impropers guessed from the bonds (guessangles ...), atom attributes guessed from
 * others (guessatom, VMD's topotools rules), new molecules from selections (combine, for
 * mergemols and selections2mol) and periodic replicas (replicate), and LAMMPS data files
 * read and written through the lammpsdata plugin with an atom style (readdata, writedata). */
#include "config.h"
#include "commands/atomsel.h"
#include "commands/commands.h"
#include "commands/topo.h"
#include "fileio/load.h"
#include "fileio/write.h"
#include "molecule/combine.h"
#include "molecule/elements.h"
#include "molecule/molset.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- guessing terms */

/* The bonded neighbours of atom i inside the selection. */
static size_t neighbours(const ms_topo_sel *t, uint32_t i, const uint32_t **to, uint32_t *buf,
                         size_t cap)
{
    const ms_molecule *m = t->m;
    size_t n = 0;
    *to = buf;
    for (uint32_t k = m->has_bonds ? m->bonds.start[i] : 0;
         m->has_bonds && k < m->bonds.start[i + 1] && n < cap; k++)
        if (t->in[m->bonds.to[k]]) buf[n++] = m->bonds.to[k];
    return n;
}

static int add_typed(ms_molecule *m, int kind, const uint32_t *at, ms_error *err)
{
    char name[256];
    ms_topo_joined_type(m, at, ms_term_width(kind), kind == MS_TERM_IMPROPER, name, sizeof name);
    ms_str ty = ms_strtab_intern_cstr(m->strings, name);
    if (ty == MS_STR_NONE) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    return ms_terms_add(m, kind, at, ty, err);
}

#define MAX_NB 64

static int guess_angles(ms_topo_sel *t, ms_error *err)
{
    uint32_t buf[MAX_NB];
    for (size_t q = 0; q < t->n; q++) {
        uint32_t j = t->atoms[q];
        const uint32_t *nb;
        size_t n = neighbours(t, j, &nb, buf, MAX_NB);
        for (size_t a = 0; a < n; a++)
            for (size_t b = a + 1; b < n; b++) {
                uint32_t at[3] = {nb[a], j, nb[b]};
                if (add_typed(t->m, MS_TERM_ANGLE, at, err)) return -1;
            }
    }
    return 0;
}

static int guess_dihedrals(ms_topo_sel *t, ms_error *err)
{
    uint32_t bj[MAX_NB], bk[MAX_NB];
    for (size_t q = 0; q < t->n; q++) {
        uint32_t j = t->atoms[q];
        const uint32_t *nj, *nk;
        size_t n = neighbours(t, j, &nj, bj, MAX_NB);
        for (size_t x = 0; x < n; x++) {
            uint32_t k = nj[x];
            if (k <= j) continue;
            size_t m = neighbours(t, k, &nk, bk, MAX_NB);
            for (size_t a = 0; a < n; a++)
                for (size_t b = 0; b < m; b++) {
                    uint32_t at[4] = {nj[a], j, k, nk[b]};
                    if (at[0] == k || at[3] == j || at[0] == at[3]) continue;
                    if (add_typed(t->m, MS_TERM_DIHEDRAL, at, err)) return -1;
                }
        }
    }
    return 0;
}

/* The dihedral angle (degrees) of four positions. */
static double dihedral(const float *p0, const float *p1, const float *p2, const float *p3)
{
    double b0[3], b1[3], b2[3], n1[3], n2[3], m1[3];
    for (int d = 0; d < 3; d++) b0[d] = p1[d] - p0[d], b1[d] = p2[d] - p1[d], b2[d] = p3[d] - p2[d];
#define CROSS(o, u, v)                                                                          \
    o[0] = u[1] * v[2] - u[2] * v[1], o[1] = u[2] * v[0] - u[0] * v[2],                        \
    o[2] = u[0] * v[1] - u[1] * v[0]
    CROSS(n1, b0, b1);
    CROSS(n2, b1, b2);
    CROSS(m1, n1, b1);
#undef CROSS
    double lb1 = sqrt(b1[0] * b1[0] + b1[1] * b1[1] + b1[2] * b1[2]);
    double x = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
    double y = (m1[0] * n2[0] + m1[1] * n2[1] + m1[2] * n2[2]) / (lb1 > 0 ? lb1 : 1);
    return atan2(y, x) * 180.0 / M_PI;
}

/* An improper for every atom with three bonds whose four atoms lie in a plane within
 * tol degrees: the centre first, then its neighbours. */
static int guess_impropers(ms_topo_sel *t, double tol, ms_error *err)
{
    if (t->frame < 0) {
        ms_error_set(err, "molecule %d has no coordinates", t->m->id);
        return -1;
    }
    const float *pos = ms_mol_frame_pos(t->m, (size_t)t->frame, err);
    if (!pos) return -1;
    uint32_t buf[MAX_NB];
    for (size_t q = 0; q < t->n; q++) {
        uint32_t c = t->atoms[q];
        const uint32_t *nb;
        if (neighbours(t, c, &nb, buf, MAX_NB) != 3) continue;
        double phi = fabs(dihedral(pos + 3 * c, pos + 3 * nb[0], pos + 3 * nb[1], pos + 3 * nb[2]));
        if (phi > tol && phi < 180.0 - tol) continue;
        uint32_t at[4] = {c, nb[0], nb[1], nb[2]};
        if (add_typed(t->m, MS_TERM_IMPROPER, at, err)) return -1;
    }
    return 0;
}

int ms_topo_guessterms(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *w = Tcl_GetString(objv[1]);
    int kind = strstr(w, "angle") ? MS_TERM_ANGLE
             : strstr(w, "dihedral") ? MS_TERM_DIHEDRAL : MS_TERM_IMPROPER;
    double tol = 5.0;
    if (objc > 3 && ms_arg_double_range(interp, objv[3], "tolerance", 0, 90, &tol))
        return TCL_ERROR;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    ms_error err = {{0}};
    int rc = ms_topo_drop_inside(&t, kind) ? -1
           : kind == MS_TERM_ANGLE         ? guess_angles(&t, &err)
           : kind == MS_TERM_DIHEDRAL      ? guess_dihedrals(&t, &err)
                                           : guess_impropers(&t, tol, &err);
    if (rc == 0) ms_molset_emit(&app->mols, MS_EV_STRUCTURE, t.m, NULL);
    ms_topo_sel_close(&t);
    if (rc) return ms_cmd_error(interp, "%s: %s", ms_args_where(), err.msg[0] ? err.msg : "out of memory");
    return TCL_OK;
}

/* ---------------------------------------------------------------- guessatom */

/* The element whose standard mass is nearest (within 0.5), 0 when none. */
static int element_of_mass(float mass)
{
    int best = 0;
    double bd = 0.5;
    for (int z = 1; z < MS_NUM_ELEMENTS && mass > 0; z++) {
        double d = fabs(ms_element_mass(z) - mass);
        if (d < bd) bd = d, best = z;
    }
    return best;
}

enum { GA_ELEMENT, GA_MASS, GA_RADIUS, GA_NAME, GA_TYPE };
static const char *const ga_what[] = {"element", "mass", "radius", "name", "type", NULL};

/* Which sources each attribute may be guessed from (VMD's topotools). */
static const char *const ga_from[][4] = {
    {"mass", "name", "type", NULL}, {"element", NULL}, {"element", NULL},
    {"element", "type", NULL},      {"element", "name", NULL}};

static int guess_one(ms_molecule *m, uint32_t i, int what, const char *from)
{
    ms_atoms *a = &m->atoms;
    const char *sym = ms_element_symbol(a->atomicnumber[i]);
    switch (what) {
    case GA_ELEMENT:
        a->atomicnumber[i] = (uint8_t)(!strcmp(from, "mass") ? element_of_mass(a->mass[i])
                         : ms_element_guess(ms_mol_str(m, !strcmp(from, "name") ? a->name[i]
                                                                                : a->type[i]),
                                            ms_mol_str(m, a->resname[i])));
        return 0;
    case GA_MASS:
        a->mass[i] = ms_element_mass(a->atomicnumber[i]);
        return 0;
    case GA_RADIUS:
        a->radius[i] = ms_element_vdw_radius(a->atomicnumber[i]);
        return 0;
    default: {
        const char *src = !strcmp(from, "element") ? sym
                        : ms_mol_str(m, !strcmp(from, "name") ? a->name[i] : a->type[i]);
        ms_str s = ms_strtab_intern_cstr(m->strings, src);
        if (s == MS_STR_NONE) return -1;
        (what == GA_NAME ? a->name : a->type)[i] = s;
        return 0;
    }
    }
}

int ms_topo_guessatom(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int what;
    if (ms_arg_choice(interp, objv[3], ga_what, "attribute", &what)) return TCL_ERROR;
    int from;
    if (ms_arg_choice(interp, objv[4], ga_from[what], "source", &from)) return TCL_ERROR;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    int rc = 0;
    for (size_t k = 0; k < t.n && !rc; k++) rc = guess_one(t.m, t.atoms[k], what, ga_from[what][from]);
    if (!rc) ms_molset_emit(&app->mols, MS_EV_STRUCTURE, t.m, NULL);
    ms_topo_sel_close(&t);
    return rc ? ms_cmd_error(interp, "%s: out of memory", ms_args_where()) : TCL_OK;
}

/* ---------------------------------------------------------------- new molecules */

/* Add a combined molecule to the set as a loaded one; its id is the result. */
static int adopt(ms_app *app, Tcl_Interp *interp, ms_molecule *m, ms_error *err)
{
    if (!m || ms_molset_add(&app->mols, m, err)) {
        ms_mol_free(m);
        return ms_cmd_error(interp, "%s: %s", ms_args_where(), err->msg);
    }
    if (m->nframes) ms_molset_set_frame(&app->mols, m, 0);
    if (m->atoms.n) ms_molset_emit(&app->mols, MS_EV_STRUCTURE_LOADED, m, NULL);
    Tcl_SetObjResult(interp, Tcl_NewIntObj(m->id));
    return TCL_OK;
}

static void free_parts(ms_topo_sel *sels, ms_mol_part *parts, int n)
{
    for (int k = 0; k < n; k++) ms_topo_sel_close(&sels[k]);
    free(sels);
    free(parts);
}

int ms_topo_combine(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj **el;
    int ne, all;
    if (Tcl_ListObjGetElements(interp, objv[2], &ne, &el) != TCL_OK ||
        ms_arg_bool(interp, objv[3], "all frames", &all))
        return TCL_ERROR;
    if (ne == 0) return ms_cmd_error(interp, "%s: no selections given", ms_args_where());
    ms_topo_sel *sels = calloc((size_t)ne, sizeof *sels);
    ms_mol_part *parts = calloc((size_t)ne, sizeof *parts);
    if (!sels || !parts) {
        free_parts(sels, parts, 0);
        return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
    }
    for (int k = 0; k < ne; k++) {
        if (ms_topo_sel_open(app, interp, el[k], &sels[k])) {
            free_parts(sels, parts, k);
            return TCL_ERROR;
        }
        parts[k] = (ms_mol_part){sels[k].m, sels[k].atoms, sels[k].n, sels[k].frame};
    }
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_combine(parts, (size_t)ne, 1, NULL, all, &err);
    free_parts(sels, parts, ne);
    return adopt(app, interp, m, &err);
}

int ms_topo_replicate(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int n[3];
    for (int d = 0; d < 3; d++)
        if (ms_arg_int(interp, objv[3 + d], "replica count", 1, 1000, &n[d])) return TCL_ERROR;
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    double v[3][3];
    if (t.frame < 0 || !ms_cell_vectors(t.m->frames[t.frame].cell, v)) {
        ms_topo_sel_close(&t);
        return ms_cmd_error(interp, "%s: molecule %d has no unit cell", ms_args_where(), t.m->id);
    }
    size_t nc = (size_t)n[0] * (size_t)n[1] * (size_t)n[2], c = 0;
    float (*shift)[3] = malloc(nc * sizeof *shift);
    ms_error err = {{0}};
    ms_molecule *m = NULL;
    for (int i = 0; shift && i < n[0]; i++)
        for (int j = 0; j < n[1]; j++)
            for (int k = 0; k < n[2]; k++, c++)
                for (int d = 0; d < 3; d++)
                    shift[c][d] = (float)(i * v[0][d] + j * v[1][d] + k * v[2][d]);
    ms_mol_part part = {t.m, t.atoms, t.n, t.frame};
    if (!shift) ms_error_set(&err, "out of memory");
    else m = ms_mol_combine(&part, 1, nc, (const float(*)[3])shift, 0, &err);
    for (size_t f = 0; m && f < m->nframes; f++)
        for (int d = 0; d < 3; d++) m->frames[f].cell[d] *= (float)n[d];
    free(shift);
    ms_topo_sel_close(&t);
    return adopt(app, interp, m, &err);
}

/* ---------------------------------------------------------------- LAMMPS data files */

static const char *const lammps_styles[] = {"auto", "atomic", "bond", "angle", "molecular",
                                            "charge", "full", NULL};

/* "atom_style=<style>" for the plugin ("" for auto). */
static int style_option(Tcl_Interp *interp, Tcl_Obj *word, char *out, size_t n)
{
    int k;
    if (ms_arg_choice(interp, word, lammps_styles, "atom style", &k)) return TCL_ERROR;
    if (k == 0) out[0] = '\0';
    else snprintf(out, n, "atom_style=%s", lammps_styles[k]);
    return TCL_OK;
}

int ms_topo_readdata(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    char opt[64];
    if (style_option(interp, objv[3], opt, sizeof opt)) return TCL_ERROR;
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.type = "lammpsdata";
    o.waitfor = -1;
    o.options = opt;
    return ms_cmd_load(app, interp, "topo readlammpsdata", Tcl_GetString(objv[2]), &o, NULL);
}

int ms_topo_writedata(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    char opt[64];
    if (style_option(interp, objv[4], opt, sizeof opt)) return TCL_ERROR;
    if (!opt[0]) snprintf(opt, sizeof opt, "atom_style=full");
    ms_topo_sel t;
    if (ms_topo_sel_open(app, interp, objv[2], &t)) return TCL_ERROR;
    ms_write_opts o;
    ms_write_opts_default(&o);
    o.type = "lammpsdata";
    o.atoms = t.atoms;
    o.natoms = t.n;
    o.first = o.last = t.frame;
    o.options = opt;
    ms_error err = {{0}};
    const char *path = Tcl_GetString(objv[3]);
    long rc = t.frame < 0 ? (ms_error_set(&err, "molecule %d has no coordinates", t.m->id), -1)
                          : ms_write_file(&app->plugins, t.m, path, &o, &err);
    ms_topo_sel_close(&t);
    if (rc < 0) return ms_cmd_error(interp, "topo writelammpsdata: %s: %s", path, err.msg);
    return TCL_OK;
}
