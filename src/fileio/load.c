/* load.c: reading files into molecules. A structure sink turns a plugin's atom records into
 * the molecule's arrays (interning strings, filling defaults); a loader streams frames; both
 * undo everything on error so a failed load leaves no trace. */
#include "config.h"
#include "fileio/load.h"
#include "fileio/assembly.h"
#include "molecule/analysis.h"
#include "molecule/elements.h"
#include "molecule/molecule.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct ms_loader {
    const ms_plugin *p;
    void *h;
    char *path;
    long natoms;
    long next_index;       /* file index of the frame read_frame returns next */
    long first, last, step;
    int with_vel;
    ms_asm_plan *plan;        /* frames are read into scratch and expanded (assemblies) */
    float *scratch_pos, *scratch_vel;
    float *probe_vel;         /* offered to a reader of frames alone while with_vel is 0 */
    long nread;               /* frames of this file added to the molecule so far */
    int stream;               /* frames are indexed, not kept: the handle is the stream's */
} ms_loader;

void ms_load_opts_default(ms_load_opts *o)
{
    memset(o, 0, sizeof *o);
    o->last = -1;
    o->step = 1;
    o->waitfor = 1;
    o->filebonds = 1;
    o->autobonds = 1;
}

/* ================================================================ the structure sink */

enum { F_NAME, F_TYPE, F_RESNAME, F_SEGNAME, F_CHAIN, F_NFIELDS };

typedef struct sink_state {
    ms_struct_sink sink;   /* first member: the plugin sees this */
    ms_molecule *m;
    ms_error *err;
    float *pos, *vel;      /* first-frame positions/velocities, 3 per atom */
    size_t pos_cap, vel_cap;
    int any_pos, any_vel;
    float cell[6];
    int has_cell, has_time;
    double time;
    uint32_t *pairs;       /* file bonds */
    float *orders;
    size_t npairs, pairs_cap, orders_cap;
    int any_order, bonds_complete;
    ms_str *btypes;        /* per file bond, MS_STR_NONE for none; NULL until one has one */
    size_t btypes_cap, nbtypes;  /* btypes[0 .. nbtypes) are set */
    ms_ss_range *ss;
    size_t nss, ss_cap;
    ms_str last_id[F_NFIELDS];
    const char *const *strings[F_NFIELDS]; /* set_strings' tables */
    ms_str *interned[F_NFIELDS];  /* their ids, MS_STR_NONE until an atom uses one */
    size_t nstrings[F_NFIELDS];
    char *remarks;
    size_t remarks_len, remarks_cap;
    ms_asm_plan asm_all;      /* every generator the file reported */
} sink_state;

static ms_str sink_intern(sink_state *st, int field, const char *s)
{
    if (!s) s = "";
    ms_str last = st->last_id[field];
    if (last != MS_STR_NONE && strcmp(ms_mol_str(st->m, last), s) == 0) return last;
    ms_str id = ms_strtab_intern_cstr(st->m->strings, s);
    st->last_id[field] = id;
    return id;
}

static int sink_reserve(ms_struct_sink *s, size_t natoms)
{
    sink_state *st = (sink_state *)s;
    if (natoms > ((size_t)1 << 31)) natoms = (size_t)1 << 31; /* a hint, not a promise */
    return ms_mol_reserve_atoms(st->m, natoms, st->err);
}

static char blank_to_nul(char c) { return c == ' ' ? '\0' : c; }

/* Keep a first-frame xyz buffer as long as the atom arrays (same capacity, no slack). */
static int sink_grow_xyz(float **buf, size_t *cap, size_t atoms_cap)
{
    if (*cap >= atoms_cap) return 0;
    float *p = realloc(*buf, atoms_cap * 3 * sizeof(float));
    if (!p) return -1;
    *buf = p;
    *cap = atoms_cap;
    return 0;
}

/* The xyz of atoms i .. i+n-1 into a first-frame buffer: src (3n floats), or zeros when
 * src is NULL and an earlier atom had some (the buffer starts when the first atom does). */
static int sink_put_xyz(float **buf, size_t *cap, int *any, const float *src, size_t i,
                        size_t n, size_t atoms_cap)
{
    if (!src && !*any) return 0;
    if (sink_grow_xyz(buf, cap, atoms_cap)) return -1;
    if (!*any) memset(*buf, 0, 3 * sizeof(float) * i);
    *any = 1;
    if (src)
        memcpy(*buf + 3 * i, src, 3 * sizeof(float) * n);
    else
        memset(*buf + 3 * i, 0, 3 * sizeof(float) * n);
    return 0;
}

static int sink_add_atom(ms_struct_sink *s, const ms_atom_in *in)
{
    sink_state *st = (sink_state *)s;
    ms_molecule *m = st->m;
    if (m->atoms.n >= 0x7fffffffu) {
        ms_error_set(st->err, "more than 2^31 atoms");
        return -1;
    }
    long li = ms_mol_add_blank_atom(m, st->err);
    if (li < 0) return -1;
    size_t i = (size_t)li;
    ms_atoms *a = &m->atoms;
    a->name[i] = sink_intern(st, F_NAME, in->name);
    a->type[i] = sink_intern(st, F_TYPE, in->type);
    a->resname[i] = sink_intern(st, F_RESNAME, in->resname);
    a->segname[i] = sink_intern(st, F_SEGNAME, in->segname);
    a->chain[i] = sink_intern(st, F_CHAIN, in->chain);
    for (int f = 0; f < F_NFIELDS; f++)
        if (st->last_id[f] == MS_STR_NONE) {
            ms_error_set(st->err, "out of memory for atom names");
            return -1;
        }
    a->resid[i] = in->resid;
    a->insertion[i] = blank_to_nul(in->insertion);
    a->altloc[i] = blank_to_nul(in->altloc);
    if (in->hetero) a->flags[i] |= MS_AF_HETERO;
    unsigned has = in->has;
    if (has & MS_HAS_BETA) a->beta[i] = in->beta;
    if (has & MS_HAS_OCCUPANCY) a->occupancy[i] = in->occupancy;
    if (has & MS_HAS_CHARGE) a->charge[i] = in->charge;
    if (has & MS_HAS_MASS) a->mass[i] = in->mass;
    if (has & MS_HAS_RADIUS) a->radius[i] = in->radius;
    int z = 0;
    if ((has & MS_HAS_ATOMICNUMBER) && in->atomicnumber > 0 && in->atomicnumber < 119)
        z = in->atomicnumber;
    else if (in->element && in->element[0])
        z = ms_element_from_symbol(in->element);
    a->atomicnumber[i] = (uint8_t)z;
    ms_analysis_atom_defaults(m, i, has & MS_HAS_MASS, has & MS_HAS_RADIUS, z > 0);

    if (sink_put_xyz(&st->pos, &st->pos_cap, &st->any_pos, has & MS_HAS_POS ? &in->x : NULL,
                     i, 1, a->cap) ||
        sink_put_xyz(&st->vel, &st->vel_cap, &st->any_vel, has & MS_HAS_VEL ? &in->vx : NULL,
                     i, 1, a->cap))
        goto oom;
    return 0;
oom:
    ms_error_set(st->err, "out of memory for coordinates of %zu atoms", a->n);
    return -1;
}

/* ---------------------------------------------------------------- atoms in bulk */

static const char *const sink_field_name[F_NFIELDS] = {"atom name", "atom type", "residue name",
                                                       "segment name", "chain"};

static int sink_set_strings(ms_struct_sink *s, int field, size_t n, const char *const *strings)
{
    sink_state *st = (sink_state *)s;
    if (field < 0 || field >= F_NFIELDS) {
        ms_error_set(st->err, "the reader gave strings for unknown field %d", field);
        return -1;
    }
    ms_str *ids = ms_alloc_array(n ? n : 1, sizeof *ids);
    if (!ids) {
        ms_error_set(st->err, "out of memory for %zu %s strings", n, sink_field_name[field]);
        return -1;
    }
    for (size_t k = 0; k < n; k++) ids[k] = MS_STR_NONE;
    free(st->interned[field]);
    st->interned[field] = ids;
    st->strings[field] = strings;
    st->nstrings[field] = n;
    return 0;
}

/* An error naming atom i's index x of field f, outside its table. */
static int bad_index(sink_state *st, size_t i, int f, uint32_t x)
{
    ms_error_set(st->err, "atom %zu: %s index %u is outside its table of %zu", i + 1,
                 sink_field_name[f], (unsigned)x, st->nstrings[f]);
    return -1;
}

/* Every string index of c (atoms first..) names a string set_strings gave. */
static int bulk_check(sink_state *st, const ms_atom_columns *c, size_t first)
{
    for (int f = 0; f < F_NFIELDS; f++)
        for (size_t i = 0; c->str[f] && i < c->n; i++)
            if (c->str[f][i] >= st->nstrings[f]) return bad_index(st, first + i, f, c->str[f][i]);
    return 0;
}

/* The string fields of atoms first.., interned atom by atom in the order add_atom would. */
static int bulk_strings_ordered(sink_state *st, const ms_atom_columns *c, size_t first)
{
    ms_atoms *a = &st->m->atoms;
    ms_str *dst[F_NFIELDS] = {a->name + first, a->type + first, a->resname + first,
                              a->segname + first, a->chain + first};
    for (size_t i = 0; i < c->n; i++)
        for (int f = 0; f < F_NFIELDS; f++) {
            ms_str id;
            if (!c->str[f]) {
                id = sink_intern(st, f, "");
            } else if ((id = st->interned[f][c->str[f][i]]) == MS_STR_NONE) {
                id = ms_strtab_intern_cstr(st->m->strings, st->strings[f][c->str[f][i]]);
                st->interned[f][c->str[f][i]] = id;
            }
            if (id == MS_STR_NONE) {
                ms_error_set(st->err, "out of memory for atom names");
                return -1;
            }
            dst[f][i] = id;
        }
    return 0;
}

/* A string index a chunk names before it is interned: where it first appears. Its slot in
 * interned[] holds STR_PENDING until the chunk's new strings are interned in atom order. */
#define STR_PENDING (MS_STR_NONE - 1)   /* never an id: a table cannot hold 2^32 - 2 strings */
typedef struct first_use {
    size_t i;
    int f;
} first_use;

static int first_use_cmp(const void *a, const void *b)
{
    const first_use *x = a, *y = b;
    if (x->i != y->i) return x->i < y->i ? -1 : 1;
    return x->f - y->f;
}

/* The column of field f: ids of known strings; the first use of each new one appended to
 * *uses. 1 when some atom's id is pending, -1 when memory runs out. */
static int bulk_column(sink_state *st, const ms_atom_columns *c, size_t first, int f,
                       ms_str *d, first_use **uses, size_t *nuses, size_t *cap)
{
    const uint32_t *x = c->str[f];
    ms_str *ids = st->interned[f];
    size_t n = c->n, nstr = st->nstrings[f];
    int pending = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t xi = x[i];
        if (xi >= nstr) return bad_index(st, first + i, f, xi);
        ms_str id = ids[xi];
        d[i] = id;
        if (id < STR_PENDING) continue;
        pending = 1;
        if (id == STR_PENDING) continue;
        if (ms_grow((void **)uses, cap, *nuses + 1, sizeof **uses)) {
            ms_error_set(st->err, "out of memory for atom names");
            return -1;
        }
        (*uses)[(*nuses)++] = (first_use){i, f};
        ids[xi] = STR_PENDING;
    }
    return pending;
}

/* The string fields of atoms first.., a column at a time; strings new to the molecule are
 * interned in the order add_atom would meet them (atom by atom, field by field), so the
 * ids are the same. */
static int bulk_strings(sink_state *st, const ms_atom_columns *c, size_t first)
{
    for (int f = 0; f < F_NFIELDS; f++)
        if (!c->str[f]) return bulk_check(st, c, first) || bulk_strings_ordered(st, c, first);
    ms_atoms *a = &st->m->atoms;
    ms_str *dst[F_NFIELDS] = {a->name + first, a->type + first, a->resname + first,
                              a->segname + first, a->chain + first};
    first_use *uses = NULL;
    size_t nuses = 0, cap = 0;
    int pending[F_NFIELDS], rc = 0;
    for (int f = 0; f < F_NFIELDS && rc >= 0; f++)
        rc = pending[f] = bulk_column(st, c, first, f, dst[f], &uses, &nuses, &cap);
    if (nuses) qsort(uses, nuses, sizeof *uses, first_use_cmp);
    for (size_t k = 0; k < nuses && rc >= 0; k++) {
        int f = uses[k].f;
        uint32_t x = c->str[f][uses[k].i];
        ms_str id = ms_strtab_intern_cstr(st->m->strings, st->strings[f][x]);
        st->interned[f][x] = id;
        if (id == MS_STR_NONE) {
            ms_error_set(st->err, "out of memory for atom names");
            rc = -1;
        }
    }
    free(uses);
    for (int f = 0; f < F_NFIELDS && rc >= 0; f++)
        for (size_t i = 0; pending[f] && i < c->n; i++)
            if (dst[f][i] >= STR_PENDING) dst[f][i] = st->interned[f][c->str[f][i]];
    return rc < 0 ? -1 : 0;
}

/* The number columns of atoms first..; absent ones stay blank for the defaults. */
static void bulk_numbers(ms_atoms *a, const ms_atom_columns *c, size_t first)
{
    size_t n = c->n;
    if (c->resid) memcpy(a->resid + first, c->resid, n * sizeof *c->resid);
    const float *src[] = {c->beta, c->occupancy, c->charge, c->mass, c->radius};
    float *dst[] = {a->beta, a->occupancy, a->charge, a->mass, a->radius};
    for (size_t k = 0; k < MS_COUNTOF(src); k++)
        if (src[k]) memcpy(dst[k] + first, src[k], n * sizeof(float));
    for (size_t i = 0; c->atomicnumber && i < n; i++) {
        int32_t z = c->atomicnumber[i];
        a->atomicnumber[first + i] = (uint8_t)(z > 0 && z < 119 ? z : 0);
    }
}

/* Room for c's atoms: the arrays they fill whole (the strings, the columns c has, mass and
 * radius, which the defaults write when absent, residues and fragments, which the analysis
 * writes) are not zeroed first. */
static long add_bulk_atoms(ms_molecule *m, const ms_atom_columns *c, ms_error *err)
{
    ms_atoms *a = &m->atoms;
    void *given[16] = {&a->name, &a->type,    &a->resname, &a->segname,
                       &a->chain, &a->mass,   &a->radius,  &a->residue, &a->fragment};
    size_t n = 9;
    const void *col[] = {c->resid, c->beta, c->occupancy, c->charge, c->atomicnumber};
    void *field[] = {&a->resid, &a->beta, &a->occupancy, &a->charge, &a->atomicnumber};
    for (size_t k = 0; k < MS_COUNTOF(col); k++)
        if (col[k]) given[n++] = field[k];
    return ms_mol_add_atoms_given(m, c->n, given, n, err);
}

static int sink_add_atoms(ms_struct_sink *s, const ms_atom_columns *c)
{
    sink_state *st = (sink_state *)s;
    ms_molecule *m = st->m;
    size_t n0 = m->atoms.n;
    if (c->n > 0x7fffffffu - n0) {
        ms_error_set(st->err, "more than 2^31 atoms");
        return -1;
    }
    if (add_bulk_atoms(m, c, st->err) < 0) return -1;
    if (bulk_strings(st, c, n0)) goto fail;
    bulk_numbers(&m->atoms, c, n0);
    ms_analysis_atoms_defaults(m, n0, c->n, c->mass != NULL, c->radius != NULL);
    if (sink_put_xyz(&st->pos, &st->pos_cap, &st->any_pos, c->pos, n0, c->n, m->atoms.cap) ||
        sink_put_xyz(&st->vel, &st->vel_cap, &st->any_vel, NULL, n0, c->n, m->atoms.cap)) {
        ms_error_set(st->err, "out of memory for coordinates of %zu atoms", m->atoms.n);
        goto fail;
    }
    return 0;
fail:
    m->atoms.n = n0;
    return -1;
}

/* Orders are kept from the first bond whose order is not 1 on: until then there is no
 * array (most files' bonds are all single), after it orders[0 .. npairs) are all set. */
static int sink_keep_orders(sink_state *st, size_t n, const float *order)
{
    size_t np = st->npairs, k = 0;
    while (!st->any_order && order && k < n && order[k] == 1.0f) k++;
    if (!st->any_order && (!order || k == n)) return 0;
    if (ms_grow((void **)&st->orders, &st->orders_cap, np + n, sizeof(float))) return -1;
    if (!st->any_order)
        for (size_t q = 0; q < np; q++) st->orders[q] = 1.0f;
    st->any_order = 1;
    for (k = 0; k < n; k++) st->orders[np + k] = order ? order[k] : 1.0f;
    return 0;
}

static int sink_add_bonds(ms_struct_sink *s, size_t n, const uint32_t *from, const uint32_t *to,
                          const float *order)
{
    sink_state *st = (sink_state *)s;
    size_t np = st->npairs;
    if (n > SIZE_MAX / 2 - np ||
        ms_grow((void **)&st->pairs, &st->pairs_cap, 2 * (np + n), sizeof(uint32_t)) ||
        sink_keep_orders(st, n, order)) {
        ms_error_set(st->err, "out of memory for bonds");
        return -1;
    }
    uint32_t *p = st->pairs + 2 * np;
    for (size_t k = 0; k < n; k++) {
        p[2 * k] = from[k];
        p[2 * k + 1] = to[k];
    }
    st->npairs += n;
    return 0;
}

static int sink_add_bond(ms_struct_sink *s, size_t i, size_t j, float order)
{
    if (i > UINT32_MAX || j > UINT32_MAX) return 0;
    uint32_t a = (uint32_t)i, b = (uint32_t)j;
    return sink_add_bonds(s, 1, &a, &b, &order);
}

static int sink_add_typed_bond(ms_struct_sink *s, size_t i, size_t j, float order,
                               const char *type)
{
    sink_state *st = (sink_state *)s;
    if (sink_add_bond(s, i, j, order)) return -1;
    if ((!type || !*type) && !st->btypes) return 0;
    size_t k = st->npairs - 1;
    if (ms_grow((void **)&st->btypes, &st->btypes_cap, st->npairs, sizeof *st->btypes))
        goto oom;
    for (size_t q = st->nbtypes; q <= k; q++) st->btypes[q] = MS_STR_NONE;
    st->nbtypes = st->npairs;
    if (type && *type &&
        (st->btypes[k] = ms_strtab_intern_cstr(st->m->strings, type)) == MS_STR_NONE)
        goto oom;
    return 0;
oom:
    ms_error_set(st->err, "out of memory for bond types");
    return -1;
}

static int sink_add_term(ms_struct_sink *s, int kind, const size_t *atoms, const char *type)
{
    sink_state *st = (sink_state *)s;
    if (kind < 0 || kind >= MS_TERM_KINDS) {
        ms_error_set(st->err, "the reader gave a term of unknown kind %d", kind);
        return -1;
    }
    uint32_t idx[4];
    size_t w = ms_term_width(kind);
    for (size_t k = 0; k < w; k++) idx[k] = atoms[k] > UINT32_MAX ? UINT32_MAX : (uint32_t)atoms[k];
    ms_str ty = MS_STR_NONE;
    if (type && *type && (ty = ms_strtab_intern_cstr(st->m->strings, type)) == MS_STR_NONE) {
        ms_error_set(st->err, "out of memory for term types");
        return -1;
    }
    return ms_terms_add(st->m, kind, idx, ty, st->err);
}

static void sink_bonds_complete(ms_struct_sink *s) { ((sink_state *)s)->bonds_complete = 1; }

static int sink_add_ss(ms_struct_sink *s, char code, const char *chain, int resid0, char ins0,
                       int resid1, char ins1)
{
    sink_state *st = (sink_state *)s;
    if (ms_grow((void **)&st->ss, &st->ss_cap, st->nss + 1, sizeof *st->ss)) {
        ms_error_set(st->err, "out of memory for secondary structure records");
        return -1;
    }
    ms_ss_range *r = &st->ss[st->nss++];
    r->code = code;
    r->chain = ms_strtab_intern_cstr(st->m->strings, chain ? chain : "");
    r->resid0 = resid0;
    r->resid1 = resid1;
    r->insertion0 = blank_to_nul(ins0);
    r->insertion1 = blank_to_nul(ins1);
    return r->chain == MS_STR_NONE ? -1 : 0;
}

static void sink_set_cell(ms_struct_sink *s, const float cell[6])
{
    sink_state *st = (sink_state *)s;
    memcpy(st->cell, cell, sizeof st->cell);
    st->has_cell = 1;
}

static void sink_set_time(ms_struct_sink *s, double t)
{
    sink_state *st = (sink_state *)s;
    st->time = t;
    st->has_time = 1;
}

static int sink_add_remark(ms_struct_sink *s, const char *text)
{
    sink_state *st = (sink_state *)s;
    size_t len = strlen(text);
    if (st->remarks_len > (1u << 20)) return 0; /* keep the first megabyte */
    if (ms_grow((void **)&st->remarks, &st->remarks_cap, st->remarks_len + len + 2, 1)) {
        ms_error_set(st->err, "out of memory for remarks");
        return -1;
    }
    memcpy(st->remarks + st->remarks_len, text, len);
    st->remarks_len += len;
    st->remarks[st->remarks_len++] = '\n';
    st->remarks[st->remarks_len] = '\0';
    return 0;
}

static int sink_add_assembly(ms_struct_sink *s, const char *id, size_t nranges,
                             const size_t (*ranges)[2], size_t nops, const double (*ops)[12])
{
    sink_state *st = (sink_state *)s;
    return ms_asm_plan_add(&st->asm_all, id, nranges, ranges, nops, ops, st->err);
}

static void sink_init(sink_state *st, ms_molecule *m, ms_error *err)
{
    memset(st, 0, sizeof *st);
    st->m = m;
    st->err = err;
    for (int f = 0; f < F_NFIELDS; f++) st->last_id[f] = MS_STR_NONE;
    st->sink.host = st;
    st->sink.reserve = sink_reserve;
    st->sink.add_atom = sink_add_atom;
    st->sink.add_bond = sink_add_bond;
    st->sink.bonds_complete = sink_bonds_complete;
    st->sink.add_ss_range = sink_add_ss;
    st->sink.set_cell = sink_set_cell;
    st->sink.set_time = sink_set_time;
    st->sink.add_remark = sink_add_remark;
    st->sink.add_assembly = sink_add_assembly;
    st->sink.add_typed_bond = sink_add_typed_bond;
    st->sink.add_term = sink_add_term;
    st->sink.set_strings = sink_set_strings;
    st->sink.add_atoms = sink_add_atoms;
    st->sink.add_bonds = sink_add_bonds;
}

static void sink_free(sink_state *st)
{
    free(st->pos);
    free(st->vel);
    free(st->pairs);
    free(st->orders);
    free(st->btypes);
    free(st->ss);
    free(st->remarks);
    for (int f = 0; f < F_NFIELDS; f++) free(st->interned[f]);
    ms_asm_plan_free(&st->asm_all);
}

/* ================================================================ plugin choice */

const ms_plugin *ms_load_pick_plugin(const ms_registry *r, const char *path, const char *type,
                                     ms_error *err)
{
    const ms_plugin *p = NULL;
    if (type && *type) {
        p = ms_registry_find(r, type);
        if (!p) {
            char known[512] = "";
            for (size_t i = 0; i < r->n; i++) {
                size_t len = strlen(known);
                snprintf(known + len, sizeof known - len, "%s%s", i ? " " : "",
                         r->plugins[i]->name);
            }
            ms_error_set(err, "unknown file type '%s' (known types: %s)", type,
                         r->n ? known : "none: no plugins were found");
            return NULL;
        }
        return p;
    }
    p = ms_registry_for_path(r, path);
    if (!p) p = ms_registry_find(r, "pdb"); /* VMD reads unknown extensions as PDB */
    if (!p) {
        ms_error_set(err, "no plugin reads this file (searched for plugins in %s)",
                     r->searched ? r->searched : "no directory");
        return NULL;
    }
    return p;
}

/* ================================================================ loading */

static int check_readable(const char *path, ms_error *err)
{
    struct stat sb;
    if (stat(path, &sb) != 0) {
        ms_error_set(err, "%s", strerror(errno));
        return -1;
    }
    if (S_ISDIR(sb.st_mode)) {
        ms_error_set(err, "is a directory");
        return -1;
    }
    return 0;
}

static int wants_frame(long index, long first, long last, long step)
{
    return index >= first && (last < 0 || index <= last) && (index - first) % step == 0;
}

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

/* Bonds from the file and/or by distance, then residues and classification. */
static int finish_structure(ms_molecule *m, sink_state *st, const ms_load_opts *o,
                            ms_error *err)
{
    size_t n = m->atoms.n;
    if (!o->filebonds) st->npairs = 0;
    for (size_t k = 0; k < st->npairs; k++) {
        if (st->pairs[2 * k] >= n || st->pairs[2 * k + 1] >= n) {
            ms_error_set(err, "bond %zu names atom %u but the file has %zu atoms", k + 1,
                         (unsigned)(MS_MAX(st->pairs[2 * k], st->pairs[2 * k + 1]) + 1), n);
            return -1;
        }
    }
    size_t nfile = st->npairs;
    int search = o->autobonds && !(st->bonds_complete && o->filebonds);
    if (search && st->any_pos) {
        /* Distance bonds go after the file's; duplicates keep the file's order. */
        if (ms_bond_search(m, st->pos, &st->pairs, &st->npairs, &st->pairs_cap, err)) return -1;
    } else if (search) {
        m->autobonds_pending = 1;
    }
    float *orders = NULL;
    if (st->any_order && nfile) {
        orders = ms_alloc_array(st->npairs, sizeof *orders);
        if (!orders) {
            ms_error_set(err, "out of memory for bond orders");
            return -1;
        }
        memcpy(orders, st->orders, nfile * sizeof *orders);
        for (size_t k = nfile; k < st->npairs; k++) orders[k] = 1.0f;
    }
    int rc = ms_bonds_build(m, st->pairs, st->npairs, orders, err);
    free(orders);
    if (!rc && st->btypes && nfile)  /* after a later add_bond, the tail is not typed */
        rc = ms_bonds_set_types(m, st->pairs, st->btypes,
                                MS_MIN(nfile, st->nbtypes), err);
    if (rc || ms_analysis_classify(m, err)) return -1;
    if (st->nss) ms_analysis_apply_ss(m, st->ss, st->nss);
    return 0;
}

/* Turn the sink's first-frame positions into frame 0 when the range keeps it. */
static int take_first_frame(ms_molecule *m, sink_state *st, const ms_load_opts *o,
                            ms_error *err)
{
    if (!st->any_pos || !wants_frame(0, o->first, o->last, o->step)) return 0;
    if (ms_grow((void **)&m->frames, &m->frames_cap, m->nframes + 1, sizeof *m->frames)) {
        ms_error_set(err, "out of memory for frames");
        return -1;
    }
    ms_frame *f = &m->frames[m->nframes];
    memset(f, 0, sizeof *f);
    f->spos = -1;
    size_t bytes = m->atoms.n * 3 * sizeof(float);
    f->pos = realloc(st->pos, bytes ? bytes : 1);
    if (!f->pos) f->pos = st->pos;
    st->pos = NULL;
    st->pos_cap = 0;
    if (st->any_vel) {
        f->vel = realloc(st->vel, bytes ? bytes : 1);
        if (!f->vel) f->vel = st->vel;
        st->vel = NULL;
        st->vel_cap = 0;
    }
    if (st->has_cell) memcpy(f->cell, st->cell, sizeof f->cell);
    f->time = st->has_time ? st->time : 0.0;
    m->nframes++;
    return 0;
}

static ms_loader *loader_new(const ms_plugin *p, void *h, const char *path, long natoms,
                             long next_index, const ms_load_opts *o, int with_vel,
                             ms_asm_plan *plan)
{
    ms_loader *ld = calloc(1, sizeof *ld);
    if (!ld || !(ld->path = ms_strdup(path))) {
        free(ld);
        return NULL;
    }
    if (plan) {
        /* Frames come with the file's atoms: read them into scratch, then expand. */
        natoms = (long)plan->nfile;
        ld->plan = plan;
        ld->scratch_pos = ms_alloc_array(3 * plan->nfile, sizeof(float));
        ld->scratch_vel = with_vel ? ms_alloc_array(3 * plan->nfile, sizeof(float)) : NULL;
        if (!ld->scratch_pos || (with_vel && !ld->scratch_vel)) {
            free(ld->scratch_pos);
            free(ld->scratch_vel);
            free(ld->path);
            free(ld);
            return NULL;
        }
    }
    ld->p = p;
    ld->h = h;
    ld->natoms = natoms;
    ld->next_index = next_index;
    ld->first = o->first;
    ld->last = o->last;
    ld->step = o->step;
    ld->with_vel = with_vel;
    return ld;
}

static void loader_free(ms_loader *ld)
{
    if (!ld) return;
    if (ld->h && !ld->stream) ld->p->close_read(ld->h);
    if (ld->plan) {
        ms_asm_plan_free(ld->plan);
        free(ld->plan);
    }
    free(ld->scratch_pos);
    free(ld->scratch_vel);
    free(ld->probe_vel);
    free(ld->path);
    free(ld);
}

/* Where a kept frame's velocities go when it has no array for them: a buffer offered to
 * the reader, so a file of frames alone (a restart, a TRR) can say it has velocities; the
 * frame then adopts it and the frames after it get their own. NULL when out of memory. */
static float *loader_probe_vel(ms_loader *ld, const ms_molecule *m)
{
    if (!ld->probe_vel) ld->probe_vel = ms_alloc_array(3 * m->atoms.n, sizeof(float));
    return ld->probe_vel;
}

static void loader_adopt_vel(ms_loader *ld, ms_frame *f)
{
    f->vel = ld->probe_vel;
    ld->probe_vel = NULL;
    ld->with_vel = 1;
}

/* The frame file frame idx goes to, and where the reader puts it (out's pos and vel): a new
 * frame's arrays, or the loader's scratch for an assembly and for a streamed frame (read
 * once for its cell and time, its place in the file recorded). NULL with err. */
static ms_frame *frame_slot(ms_molecule *m, ms_loader *ld, long idx, ms_frame_out *out,
                            ms_error *err)
{
    ms_frame *f = NULL;
    if (ld->stream) {
        ms_perr perr = {{0}};
        long long token;
        if (ld->p->tell_frame(ld->h, &token, &perr) != MS_PLUGIN_OK)
            ms_error_set(err, "%s", perr.msg);
        else f = ms_mol_add_streamed_frame(m, token, err);
        out->pos = ld->scratch_pos;
        out->vel = ld->scratch_vel;
    } else if ((f = ms_mol_add_frame(m, ld->with_vel, err))) {
        out->pos = ld->plan ? ld->scratch_pos : f->pos;
        out->vel = ld->plan ? ld->scratch_vel : f->vel ? f->vel : loader_probe_vel(ld, m);
    }
    if (!f) ms_error_prefix(err, "frame %ld", idx);
    return f;
}

/* Read up to max frames (max < 0: all). Returns 1 more remain, 0 done, -1 error. The frames
 * appended before an error stay; the caller decides whether to roll back. */
static int loader_read(ms_molecule *m, ms_loader *ld, long max, ms_error *err)
{
    long kept = 0;
    while (max < 0 || kept < max) {
        long idx = ld->next_index;
        if (ld->last >= 0 && idx > ld->last) return 0;
        if (!ld->p->read_frame) return 0;
        ms_perr perr = {{0}};
        ms_frame_out out;
        memset(&out, 0, sizeof out);
        ms_frame *f = NULL;
        int keep = wants_frame(idx, ld->first, ld->last, ld->step);
        if (keep && !(f = frame_slot(m, ld, idx, &out, err))) return -1;
        int rc = ld->p->read_frame(ld->h, ld->natoms, &out, &perr);
        if (rc != MS_PLUGIN_OK) {
            if (keep) ms_mol_truncate_frames(m, m->nframes - 1);
            if (rc == MS_PLUGIN_EOF) return 0;
            ms_error_set(err, "frame %ld: %s", idx, perr.msg[0] ? perr.msg : "read error");
            return -1;
        }
        ld->next_index++;
        if (!keep) continue;
        if (ld->stream && out.has_vel) m->stream->with_vel = 1;
        if (!ld->plan && !ld->stream && !f->vel && out.has_vel && out.vel) loader_adopt_vel(ld, f);
        if (ld->plan && !ld->stream) {
            ms_asm_expand_xyz(ld->plan, ld->scratch_pos, f->pos, 0);
            if (f->vel && out.has_vel) ms_asm_expand_xyz(ld->plan, ld->scratch_vel, f->vel, 1);
        }
        if (out.has_cell) memcpy(f->cell, out.cell, sizeof f->cell);
        else if (m->nframes >= 2) memcpy(f->cell, m->frames[m->nframes - 2].cell, sizeof f->cell);
        f->time = out.has_time ? out.time : 0.0;
        if (f->vel && !out.has_vel) memset(f->vel, 0, m->atoms.n * 3 * sizeof(float));
        kept++;
        ld->nread++;
    }
    return 1;
}

/* ---------------------------------------------------------------- streamed frames */

/* A streamed file's reader: the loader's handle, kept open after the index pass. */
typedef struct stream_src {
    const ms_plugin *p;
    void *h;
    long natoms;
} stream_src;

static void stream_src_free(void *ud)
{
    stream_src *s = ud;
    s->p->close_read(s->h);
    free(s);
}

/* Read the frame at token into pos and vel, then put the handle back where it was (the
 * index pass may still be going on in the background). */
static int stream_read(void *ud, long long token, float *pos, float *vel, ms_error *err)
{
    stream_src *s = ud;
    ms_perr perr = {{0}}, ignored = {{0}};
    ms_frame_out out;
    memset(&out, 0, sizeof out);
    out.pos = pos;
    out.vel = vel;
    long long back;
    int rc = s->p->tell_frame(s->h, &back, &perr);
    if (rc == MS_PLUGIN_OK) rc = s->p->seek_frame(s->h, token, &perr);
    if (rc == MS_PLUGIN_OK) {
        rc = s->p->read_frame(s->h, s->natoms, &out, &perr);
        s->p->seek_frame(s->h, back, &ignored);
    }
    if (rc == MS_PLUGIN_EOF)
        ms_perr_set(&perr, "the file ends before this frame: it changed since it was read");
    if (rc != MS_PLUGIN_OK) {
        ms_error_set(err, "%s", perr.msg[0] ? perr.msg : "read error");
        return -1;
    }
    if (vel && !out.has_vel) memset(vel, 0, (size_t)s->natoms * 3 * sizeof(float));
    return 0;
}

/* The memory frames may take before a trajectory streams: 80 % of what the system can
 * still give, or MOLSCOPE_TRAJ_BUDGET (bytes, with an optional K, M or G) when that is
 * less. 0 when neither is known. */
static double frames_budget(const char **what)
{
    double budget = 0.8 * (double)ms_mem_available();
    *what = "of memory available";
    const char *env = getenv("MOLSCOPE_TRAJ_BUDGET");
    char *end;
    double v = env ? strtod(env, &end) : 0;
    if (env && end != env && v > 0) {
        int k = *end == 'K' || *end == 'k' ? 1 : *end == 'M' || *end == 'm' ? 2
                : *end == 'G' || *end == 'g' ? 3 : 0;
        v *= k == 1 ? 1e3 : k == 2 ? 1e6 : k == 3 ? 1e9 : 1;
        if (budget <= 0 || v < budget) {
            budget = v;
            *what = "of MOLSCOPE_TRAJ_BUDGET";
        }
    }
    return budget;
}

/* Whether the file's frames stream: asked (o->stream 1), or else when a file this size
 * would not fit in the budget (frames in memory take about what a binary file holds), the
 * reason then in why. Refused (-1) when asked of a format that cannot seek. */
static int wants_stream(const ms_plugin *p, const char *path, const ms_load_opts *o,
                        const ms_asm_plan *plan, char *why, size_t whylen, ms_error *err)
{
    int can = p->tell_frame && p->seek_frame && !plan;
    why[0] = '\0';
    if (o->stream > 0 && !can) {
        ms_error_set(err, "-stream: the %s format %s", p->name,
                     plan ? "cannot stream an assembly" : "cannot seek frames");
        return -1;
    }
    if (o->stream != 0 || !can) return o->stream > 0;
    struct stat sb;
    const char *what;
    double budget = frames_budget(&what);
    if (stat(path, &sb) || budget <= 0 || (double)sb.st_size <= budget) return 0;
    double size = (double)sb.st_size, gb = MS_MAX(size, budget) >= 1e9 ? 1e9 : 1e6;
    snprintf(why, whylen, "%s (%.1f %s) would not fit in the %.1f %s %s", base_name(path),
             size / gb, gb > 1e6 ? "GB" : "MB", budget / gb, gb > 1e6 ? "GB" : "MB", what);
    return 1;
}

/* Make the loader index its frames for the molecule's stream. */
static int stream_begin(ms_molecule *m, ms_loader *ld, const ms_load_opts *o, const char *why,
                        ms_error *err)
{
    stream_src *s = calloc(1, sizeof *s);
    ms_frame_source src = {s, stream_read, stream_src_free, ms_strdup(ld->path)};
    ld->scratch_pos = ms_alloc_array(3 * m->atoms.n, sizeof(float));
    ld->scratch_vel = ms_alloc_array(3 * m->atoms.n, sizeof(float));
    if (!s || !src.path || !ld->scratch_pos || !ld->scratch_vel) {
        free(s);
        free(src.path);
        ms_error_set(err, "out of memory");
        return -1;
    }
    *s = (stream_src){ld->p, ld->h, ld->natoms};
    size_t window = o->window > 0 ? (size_t)o->window : MS_STREAM_WINDOW;
    if (ms_mol_stream_start(m, &src, window, 0, err)) {
        free(s);
        free(src.path);
        return -1;
    }
    snprintf(m->stream->why, sizeof m->stream->why, "%s", why);
    ld->stream = 1;
    return 0;
}

/* Undo a stream no frame uses any more (a load that failed after stream_begin). */
static void stream_drop(ms_molecule *m, size_t nframes_before)
{
    if (!m->stream) return;
    for (size_t f = 0; f < MS_MIN(nframes_before, m->nframes); f++)
        if (m->frames[f].spos >= 0) return;
    if (m->stream->src.free) m->stream->src.free(m->stream->src.ud);
    free(m->stream->src.path);
    free(m->stream);
    m->stream = NULL;
}

/* Open a frame reader on an already-open plugin handle and read the first `waitfor` frames
 * (counting `already` frames the structure gave). Leaves a pending loader on the molecule
 * when frames remain. */
static int read_frames(ms_molecule *m, const ms_plugin *p, void *h, const char *path,
                       long next_index, long already, const ms_load_opts *o, int with_vel,
                       ms_asm_plan *plan, ms_error *err)
{
    ms_loader *ld = loader_new(p, h, path, (long)m->atoms.n, next_index, o, with_vel, plan);
    if (!ld) {
        if (plan) {
            ms_asm_plan_free(plan);
            free(plan);
        }
        p->close_read(h);
        ms_error_set(err, "out of memory");
        return -1;
    }
    char why[256];
    int stream = p->read_frame ? wants_stream(p, path, o, plan, why, sizeof why, err) : 0;
    if (stream > 0 && m->stream && o->stream <= 0) stream = 0;  /* auto: it streams a file */
    if (stream < 0 || (stream > 0 && stream_begin(m, ld, o, why, err))) {
        loader_free(ld);
        return -1;
    }
    long now = o->waitfor < 0 ? -1 : MS_MAX(0, o->waitfor - already);
    int rc = loader_read(m, ld, now, err);
    if (rc <= 0) {
        loader_free(ld);
        return rc;
    }
    m->pending = ld;
    return 0;
}

static int open_plugin(const ms_plugin *p, const char *path, long *natoms, void **h,
                       ms_error *err)
{
    ms_perr perr = {{0}};
    if (check_readable(path, err)) return -1;
    if (!p->open_read) {
        ms_error_set(err, "the %s plugin cannot read files", p->name);
        return -1;
    }
    *natoms = -1;
    *h = p->open_read(path, natoms, &perr);
    if (!*h) {
        ms_error_set(err, "%s", perr.msg[0] ? perr.msg : "cannot open");
        return -1;
    }
    return 0;
}

/* Replace the file's atoms, first-frame coordinates and bonds by assembly `id`'s copies.
 * *plan receives the plan (the frames that follow are expanded by it). */
static int apply_assembly(ms_molecule *m, sink_state *st, const char *id, ms_asm_plan **plan,
                          ms_error *err)
{
    ms_asm_plan *p = calloc(1, sizeof *p);
    if (!p) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    *plan = p;
    if (ms_asm_select(&st->asm_all, id, m->atoms.n, p, err)) return -1;
    size_t total = ms_asm_natoms(p);
    float *pos = NULL, *vel = NULL;
    if ((st->any_pos && !(pos = ms_alloc_array(3 * total, sizeof *pos))) ||
        (st->any_vel && !(vel = ms_alloc_array(3 * total, sizeof *vel)))) {
        free(pos);
        ms_error_set(err, "out of memory for an assembly of %zu atoms", total);
        return -1;
    }
    uint32_t *pairs;
    float *orders;
    size_t npairs;
    if (ms_asm_expand_pairs(p, st->pairs, st->orders, st->npairs, &pairs, &orders, &npairs,
                            err) ||
        ms_asm_expand_atoms(m, p, err)) {
        free(pos);
        free(vel);
        return -1;
    }
    if (pos) ms_asm_expand_xyz(p, st->pos, pos, 0);
    if (vel) ms_asm_expand_xyz(p, st->vel, vel, 1);
    free(st->pos);
    free(st->vel);
    st->pos = pos;
    st->vel = vel;
    st->pos_cap = pos ? total : 0;
    st->vel_cap = vel ? total : 0;
    free(st->pairs);
    free(st->orders);
    st->pairs = pairs;
    st->orders = orders;
    st->npairs = st->pairs_cap = st->orders_cap = npairs;
    return 0;
}

/* Read the structure (and first frame) of an open file into m, then finish analysis. */
static int read_structure_into(ms_molecule *m, const ms_plugin *p, void *h, long natoms,
                               const ms_load_opts *o, sink_state *st, ms_asm_plan **plan,
                               ms_error *err)
{
    if (p->read_structure) {
        ms_perr perr = {{0}};
        if (p->read_structure(h, &st->sink, &perr) != MS_PLUGIN_OK) {
            if (!err->msg[0] || perr.msg[0]) ms_error_set(err, "%s", perr.msg[0] ? perr.msg : "read error");
            return -1;
        }
    } else {
        if (natoms < 0) {
            ms_error_set(err, "the %s format has no structure and gave no atom count", p->name);
            return -1;
        }
        if (ms_mol_reserve_atoms(m, (size_t)natoms, err)) return -1;
        for (long i = 0; i < natoms; i++) {
            if (ms_mol_add_blank_atom(m, err) < 0) return -1;
            ms_analysis_atom_defaults(m, (size_t)i, 0, 0, 0);
        }
    }
    if (m->atoms.n == 0) {
        ms_error_set(err, "no atoms found");
        return -1;
    }
    ms_mol_shrink(m);
    if (o->assembly && apply_assembly(m, st, o->assembly, plan, err)) return -1;
    return finish_structure(m, st, o, err);
}

/* A volume set's size from its description: refuse empty and absurd grids. */
static int volume_size(const ms_volume_meta *meta, int k, size_t *n, ms_error *err)
{
    size_t t = 1;
    for (int d = 0; d < 3; d++)
        if (meta->n[d] < 1 || meta->n[d] > (1L << 30) || ms_mul_size(t, (size_t)meta->n[d], &t)) {
            ms_error_set(err, "volume set %d: bad grid size %ld x %ld x %ld", k, meta->n[0],
                         meta->n[1], meta->n[2]);
            return -1;
        }
    if (t > ((size_t)1 << 36)) {
        ms_error_set(err, "volume set %d: %zu points is more than 2^36", k, t);
        return -1;
    }
    *n = t;
    return 0;
}

/* One volume set of an open file into an ms_volume. */
static int read_volume(const ms_plugin *p, void *h, int k, const ms_volume_meta *meta,
                       const char *path, ms_volume *v, ms_error *err)
{
    size_t n;
    memset(v, 0, sizeof *v);
    if (volume_size(meta, k, &n, err)) return -1;
    v->data = ms_alloc_array(n, sizeof(float));
    v->name = ms_strdup(meta->name[0] ? meta->name : base_name(path));
    if (!v->data || !v->name) {
        ms_volume_clear(v);
        ms_error_set(err, "volume set %d: out of memory for %zu points", k, n);
        return -1;
    }
    ms_perr perr = {{0}};
    if (p->read_volume_data(h, k, v->data, &perr) != MS_PLUGIN_OK) {
        ms_volume_clear(v);
        ms_error_set(err, "volume set %d: %s", k, perr.msg[0] ? perr.msg : "read error");
        return -1;
    }
    for (int d = 0; d < 3; d++) {
        v->n[d] = (int)meta->n[d];
        v->origin[d] = (float)meta->origin[d];
        for (int e = 0; e < 3; e++) v->delta[d][e] = (float)meta->delta[d][e];
    }
    return 0;
}

/* Every volume set of an open file, appended to m->volumes; on error none is kept. Returns
 * the number read, or -1. */
static long read_volumes(ms_molecule *m, const ms_plugin *p, void *h, const char *path,
                         ms_error *err)
{
    size_t before = m->nvolumes;
    if (!p->read_volume_meta || !p->read_volume_data) return 0;
    for (int k = 0;; k++) {
        ms_volume_meta meta;
        memset(&meta, 0, sizeof meta);
        ms_perr perr = {{0}};
        int rc = p->read_volume_meta(h, k, &meta, &perr);
        if (rc == MS_PLUGIN_EOF) break;
        ms_volume v;
        if (rc != MS_PLUGIN_OK) {
            ms_error_set(err, "volume set %d: %s", k, perr.msg[0] ? perr.msg : "read error");
            goto fail;
        }
        meta.name[sizeof meta.name - 1] = '\0';
        if (read_volume(p, h, k, &meta, path, &v, err) || ms_mol_add_volume(m, &v, err) < 0)
            goto fail;
    }
    return (long)(m->nvolumes - before);
fail:
    while (m->nvolumes > before) ms_mol_delete_volume(m, m->nvolumes - 1);
    return -1;
}

/* A file of volumes only: a molecule with no atoms holding them. */
static ms_molecule *load_volume_file(const ms_plugin *p, const char *path, ms_error *err)
{
    long natoms;
    void *h;
    if (open_plugin(p, path, &natoms, &h, err)) return NULL;
    ms_molecule *m = ms_mol_new(err);
    long got = m ? read_volumes(m, p, h, path, err) : -1;
    p->close_read(h);
    if (got == 0) ms_error_set(err, "no volumetric data found");
    if (got <= 0 || !(m->name = ms_strdup(base_name(path))) ||
        ms_mol_add_file(m, path, p->name, err) || ms_bonds_build(m, NULL, 0, NULL, err) ||
        ms_analysis_classify(m, err)) {
        if (!err->msg[0]) ms_error_set(err, "out of memory");
        ms_mol_free(m);
        return NULL;
    }
    return m;
}

static int volume_only(const ms_plugin *p)
{
    return (p->caps & MS_CAN_READ_VOLUME) && !(p->caps & MS_CAN_READ_STRUCTURE) &&
           !(p->caps & MS_CAN_READ_FRAMES);
}

ms_molecule *ms_load_new(const ms_registry *r, const char *path, const ms_load_opts *o,
                         ms_error *err)
{
    err->msg[0] = '\0';
    const ms_plugin *p = ms_load_pick_plugin(r, path, o->type, err);
    if (!p) return NULL;
    if (volume_only(p)) return load_volume_file(p, path, err);
    if (!(p->caps & (MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES))) {
        ms_error_set(err, "the %s plugin cannot read files", p->name);
        return NULL;
    }
    if (o->assembly && !p->read_structure) {
        ms_error_set(err, "the %s format holds no biological assemblies", p->name);
        return NULL;
    }
    long natoms;
    void *h;
    if (open_plugin(p, path, &natoms, &h, err)) return NULL;
    ms_molecule *m = ms_mol_new(err);
    if (!m) {
        p->close_read(h);
        return NULL;
    }
    sink_state st;
    ms_asm_plan *plan = NULL;
    sink_init(&st, m, err);
    st.sink.options = o->options;
    if (natoms > 0) sink_reserve(&st.sink, (size_t)natoms);
    if (read_structure_into(m, p, h, natoms, o, &st, &plan, err) ||
        take_first_frame(m, &st, o, err) || !(m->name = ms_strdup(base_name(path))) ||
        ms_mol_add_file(m, path, p->name, err) || read_volumes(m, p, h, path, err) < 0) {
        if (!err->msg[0]) ms_error_set(err, "out of memory");
        p->close_read(h);
        if (plan) {
            ms_asm_plan_free(plan);
            free(plan);
        }
        goto fail;
    }
    if (st.remarks) {
        m->remarks = st.remarks;
        st.remarks = NULL;
    }
    int with_vel = st.any_vel;
    long next_index = st.any_pos ? 1 : 0;
    long already = (long)m->nframes;
    sink_free(&st);
    if (read_frames(m, p, h, path, next_index, already, o, with_vel, plan, err))
        goto fail_nosink;
    if (ms_load_finish_bonds(m, err)) goto fail_nosink;
    m->frame = -1;
    if (m->nframes && ms_mol_goto(m, m->nframes - 1, err)) goto fail_nosink;
    return m;
fail:
    sink_free(&st);
fail_nosink:
    ms_loader_cancel(m);
    ms_mol_free(m);
    return NULL;
}

void ms_load_adopt(ms_molecule *dst, ms_molecule *src)
{
    ms_molecule old = *dst;
    *dst = *src;
    dst->id = old.id;
    dst->active = old.active;
    dst->displayed = old.displayed;
    dst->fixed = old.fixed;
    memcpy(dst->center, old.center, sizeof old.center);
    dst->scale = old.scale;
    memcpy(dst->rotate, old.rotate, sizeof old.rotate);
    memcpy(dst->global, old.global, sizeof old.global);
    memcpy(dst->ext, old.ext, sizeof old.ext);
    memset(old.ext, 0, sizeof old.ext);
    ms_mol_free_contents(&old);
    free(src);
}

/* Frames from a file into a molecule that already has atoms. */
static int add_frames(const ms_plugin *p, ms_molecule *m, const char *path,
                      const ms_load_opts *o, ms_error *err)
{
    long natoms;
    void *h;
    if (open_plugin(p, path, &natoms, &h, err)) return -1;
    long next_index = 0;
    int with_vel = 0;
    size_t before = m->nframes;
    if (p->read_structure) {
        /* A structure format read as a trajectory (a PDB added to a PSF): parse it into a
         * scratch molecule and take its coordinates. */
        ms_molecule *tmp = ms_mol_new(err);
        if (!tmp) {
            p->close_read(h);
            return -1;
        }
        sink_state st;
        sink_init(&st, tmp, err);
        st.sink.options = o->options;
        ms_perr perr = {{0}};
        if (p->read_structure(h, &st.sink, &perr) != MS_PLUGIN_OK) {
            ms_error_set(err, "%s", perr.msg[0] ? perr.msg : "read error");
            goto fail_tmp;
        }
        if (tmp->atoms.n != m->atoms.n) {
            ms_error_set(err, "has %zu atoms but molecule %d has %zu", tmp->atoms.n, m->id,
                         m->atoms.n);
            goto fail_tmp;
        }
        if (st.any_pos && wants_frame(0, o->first, o->last, o->step)) {
            ms_frame *f = ms_mol_add_frame(m, st.any_vel, err);
            if (!f) goto fail_tmp;
            memcpy(f->pos, st.pos, m->atoms.n * 3 * sizeof(float));
            if (st.any_vel) memcpy(f->vel, st.vel, m->atoms.n * 3 * sizeof(float));
            if (st.has_cell) memcpy(f->cell, st.cell, sizeof f->cell);
            f->time = st.has_time ? st.time : 0.0;
        }
        next_index = st.any_pos ? 1 : 0;
        with_vel = st.any_vel;
        sink_free(&st);
        ms_mol_free(tmp);
        goto frames;
    fail_tmp:
        sink_free(&st);
        ms_mol_free(tmp);
        p->close_read(h);
        return -1;
    }
    if (natoms >= 0 && (size_t)natoms != m->atoms.n) {
        ms_error_set(err, "has %ld atoms but molecule %d has %zu", natoms, m->id, m->atoms.n);
        p->close_read(h);
        return -1;
    }
frames:
    /* A structure format's first frame counts towards waitfor. */
    return read_frames(m, p, h, path, next_index, (long)(m->nframes - before), o, with_vel,
                       NULL, err);
}

/* A volume file's sets appended to a molecule's. */
static int add_volumes(const ms_plugin *p, ms_molecule *m, const char *path, ms_error *err)
{
    long natoms;
    void *h;
    size_t before = m->nvolumes;
    if (open_plugin(p, path, &natoms, &h, err)) return -1;
    long got = read_volumes(m, p, h, path, err);
    p->close_read(h);
    if (got == 0) ms_error_set(err, "no volumetric data found");
    if (got <= 0 || ms_mol_add_file(m, path, p->name, err)) {
        while (m->nvolumes > before) ms_mol_delete_volume(m, m->nvolumes - 1);
        return -1;
    }
    return 0;
}

/* Move dst's volumes in front of src's (src replaces dst's contents next). */
static int keep_volumes(ms_molecule *src, ms_molecule *dst, ms_error *err)
{
    size_t n = dst->nvolumes + src->nvolumes;
    ms_volume *v = ms_alloc_array(n, sizeof *v);
    if (!v) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    memcpy(v, dst->volumes, dst->nvolumes * sizeof *v);
    if (src->nvolumes) memcpy(v + dst->nvolumes, src->volumes, src->nvolumes * sizeof *v);
    free(src->volumes);
    free(dst->volumes);
    src->volumes = v;
    src->nvolumes = n;
    dst->volumes = NULL;
    dst->nvolumes = 0;
    return 0;
}

int ms_load_add(const ms_registry *r, ms_molecule *m, const char *path, const ms_load_opts *o,
                ms_error *err)
{
    err->msg[0] = '\0';
    const ms_plugin *p = ms_load_pick_plugin(r, path, o->type, err);
    if (!p) return -1;
    /* Files load in order: finish a previous file's pending frames first. */
    if (m->pending) {
        char *done = NULL;
        if (ms_loader_pump(m, -1, &done, err) < 0) {
            free(done);
            return -1;
        }
        free(done);
    }
    /* A map, or a file of atoms and maps (a cube) added to a molecule that has atoms: its
     * volumes only. */
    if (volume_only(p) || ((p->caps & MS_CAN_READ_VOLUME) && m->atoms.n > 0))
        return add_volumes(p, m, path, err);
    if (m->atoms.n == 0) {
        ms_molecule *src = ms_load_new(r, path, o, err);
        if (!src) return -1;
        /* Volumes the molecule held stay, before the file's own. */
        if (m->nvolumes && keep_volumes(src, m, err)) {
            ms_mol_free(src);
            return -1;
        }
        ms_load_adopt(m, src);
        return 0;
    }
    if (o->assembly) {
        ms_error_set(err, "an assembly can only be built when the file makes the structure "
                     "(molecule %d already has atoms)", m->id);
        return -1;
    }
    size_t before = m->nframes;
    int frame_before = m->frame;
    if (add_frames(p, m, path, o, err) || ms_mol_add_file(m, path, p->name, err) ||
        ms_load_finish_bonds(m, err) ||
        (m->nframes > before && ms_mol_goto(m, m->nframes - 1, err))) {
        ms_loader_cancel(m);
        ms_mol_truncate_frames(m, before);
        stream_drop(m, before);
        m->frame = frame_before;
        return -1;
    }
    return 0;
}

int ms_loader_pump(ms_molecule *m, long max_frames, char **path_done, ms_error *err)
{
    *path_done = NULL;
    ms_loader *ld = m->pending;
    if (!ld) return 0;
    int rc = loader_read(m, ld, max_frames, err);
    if (rc == 1) return 1;
    if (rc < 0) {
        size_t len = strlen(err->msg);
        snprintf(err->msg + len, sizeof err->msg - len, "; the %ld frame%s read before it %s kept",
                 ld->nread, ld->nread == 1 ? "" : "s", ld->nread == 1 ? "is" : "are");
    }
    *path_done = ld->path;
    ld->path = NULL;
    loader_free(ld);
    m->pending = NULL;
    if (rc == 0 && ms_load_finish_bonds(m, err)) return -1;
    return rc;
}

void ms_loader_cancel(ms_molecule *m)
{
    loader_free(m->pending);
    m->pending = NULL;
}

int ms_load_finish_bonds(ms_molecule *m, ms_error *err)
{
    if (!m->autobonds_pending || m->nframes == 0) return 0;
    uint32_t *pairs = NULL;
    size_t npairs = 0, cap = 0;
    /* Keep the bonds the file gave and add the distance ones. */
    if (m->has_bonds) {
        for (size_t i = 0; i < m->atoms.n; i++)
            for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
                if (m->bonds.to[k] <= i) continue;
                if (ms_grow((void **)&pairs, &cap, 2 * (npairs + 1), sizeof *pairs)) goto oom;
                pairs[2 * npairs] = (uint32_t)i;
                pairs[2 * npairs + 1] = m->bonds.to[k];
                npairs++;
            }
    }
    const float *pos0 = ms_mol_frame_pos(m, 0, err);
    if (!pos0 || ms_bond_search(m, pos0, &pairs, &npairs, &cap, err) ||
        ms_mol_set_bonds(m, npairs, pairs, NULL, err)) {
        free(pairs);
        return -1;
    }
    free(pairs);
    m->autobonds_pending = 0;
    return 0;
oom:
    free(pairs);
    ms_error_set(err, "out of memory for bonds");
    return -1;
}
