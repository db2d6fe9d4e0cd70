/* parm7.c: the AMBER topology plugin (VMD's type `parm7`: .prmtop .parm7; built a second
 * time as `parm` by parm.c for the .parm extension). Reads both header styles: AMBER 7's
 * "%FLAG name / %FORMAT(...)" sections in any order, and the older files (a title line, then
 * the sections in their fixed order and Fortran formats: 20A4, 12I6, 5E16.8). Gives atom
 * names, types, charges (AMBER's units divided by 18.2223: electrons), masses, atomic numbers
 * when present, residues (RESIDUE_LABEL, RESIDUE_POINTER; resid is the residue's 1-based
 * number), every bond (with and without hydrogen), angles, dihedrals (an entry whose fourth
 * index is negative is an improper; a negative third index only marks 1-4 terms, and the
 * extra Fourier terms of a dihedral are one dihedral) and the box (IFBOX, BOX_DIMENSIONS).
 * A topology holds no coordinates. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef PARM_TYPE_NAME
#define PARM_TYPE_NAME "parm7"
#define PARM_DESCRIPTION "AMBER 7 parameter/topology file"
#define PARM_EXTENSIONS "prmtop parm7"
#endif

#define AMBER_CHARGE_UNIT 18.2223

/* The pointers this reader uses, by their place in POINTERS. */
enum {
    P_NATOM = 0, P_NTYPES = 1, P_NBONH = 2, P_MBONA = 3, P_NTHETH = 4, P_MTHETA = 5,
    P_NPHIH = 6, P_MPHIA = 7, P_NNB = 10, P_NRES = 11, P_NUMBND = 15, P_NUMANG = 16,
    P_NPTRA = 17, P_NATYP = 18, P_NPHB = 19, P_IFBOX = 27, P_NOLD = 30
};

/* How many values a section holds, from the pointers: a * pointer (or a * NTYPES^2, a *
 * NTYPES(NTYPES+1)/2, a fixed number). */
enum { C_PTR, C_SQUARE, C_TRIANGLE, C_FIXED, C_NSPM };

typedef struct parm_sec_def {
    const char *flag;
    char kind;       /* 'a' text, 'I' integer, 'E' real */
    int keep;        /* the reader stores its values */
    int count_rule, ptr, mult;
} parm_sec_def;

/* The sections in the order of the old format; the new one names them. */
static const parm_sec_def parm_secs[] = {
    {"ATOM_NAME", 'a', 1, C_PTR, P_NATOM, 1},
    {"CHARGE", 'E', 1, C_PTR, P_NATOM, 1},
    {"MASS", 'E', 1, C_PTR, P_NATOM, 1},
    {"ATOM_TYPE_INDEX", 'I', 0, C_PTR, P_NATOM, 1},
    {"NUMBER_EXCLUDED_ATOMS", 'I', 0, C_PTR, P_NATOM, 1},
    {"NONBONDED_PARM_INDEX", 'I', 0, C_SQUARE, P_NTYPES, 1},
    {"RESIDUE_LABEL", 'a', 1, C_PTR, P_NRES, 1},
    {"RESIDUE_POINTER", 'I', 1, C_PTR, P_NRES, 1},
    {"BOND_FORCE_CONSTANT", 'E', 0, C_PTR, P_NUMBND, 1},
    {"BOND_EQUIL_VALUE", 'E', 0, C_PTR, P_NUMBND, 1},
    {"ANGLE_FORCE_CONSTANT", 'E', 0, C_PTR, P_NUMANG, 1},
    {"ANGLE_EQUIL_VALUE", 'E', 0, C_PTR, P_NUMANG, 1},
    {"DIHEDRAL_FORCE_CONSTANT", 'E', 0, C_PTR, P_NPTRA, 1},
    {"DIHEDRAL_PERIODICITY", 'E', 0, C_PTR, P_NPTRA, 1},
    {"DIHEDRAL_PHASE", 'E', 0, C_PTR, P_NPTRA, 1},
    {"SOLTY", 'E', 0, C_PTR, P_NATYP, 1},
    {"LENNARD_JONES_ACOEF", 'E', 0, C_TRIANGLE, P_NTYPES, 1},
    {"LENNARD_JONES_BCOEF", 'E', 0, C_TRIANGLE, P_NTYPES, 1},
    {"BONDS_INC_HYDROGEN", 'I', 1, C_PTR, P_NBONH, 3},
    {"BONDS_WITHOUT_HYDROGEN", 'I', 1, C_PTR, P_MBONA, 3},
    {"ANGLES_INC_HYDROGEN", 'I', 1, C_PTR, P_NTHETH, 4},
    {"ANGLES_WITHOUT_HYDROGEN", 'I', 1, C_PTR, P_MTHETA, 4},
    {"DIHEDRALS_INC_HYDROGEN", 'I', 1, C_PTR, P_NPHIH, 5},
    {"DIHEDRALS_WITHOUT_HYDROGEN", 'I', 1, C_PTR, P_MPHIA, 5},
    {"EXCLUDED_ATOMS_LIST", 'I', 0, C_PTR, P_NNB, 1},
    {"HBOND_ACOEF", 'E', 0, C_PTR, P_NPHB, 1},
    {"HBOND_BCOEF", 'E', 0, C_PTR, P_NPHB, 1},
    {"HBCUT", 'E', 0, C_PTR, P_NPHB, 1},
    {"AMBER_ATOM_TYPE", 'a', 1, C_PTR, P_NATOM, 1},
    {"TREE_CHAIN_CLASSIFICATION", 'a', 0, C_PTR, P_NATOM, 1},
    {"JOIN_ARRAY", 'I', 0, C_PTR, P_NATOM, 1},
    {"IROTAT", 'I', 0, C_PTR, P_NATOM, 1},
    /* only when IFBOX > 0 */
    {"SOLVENT_POINTERS", 'I', 1, C_FIXED, 0, 3},
    {"ATOMS_PER_MOLECULE", 'I', 0, C_NSPM, 0, 1},
    {"BOX_DIMENSIONS", 'E', 1, C_FIXED, 0, 4},
    /* new format only */
    {"ATOMIC_NUMBER", 'I', 1, C_PTR, P_NATOM, 1},
};
#define NSECS (sizeof parm_secs / sizeof parm_secs[0])
#define NOLD_SECS 32 /* the sections every old file has, before the box ones */
#define S_BOX_FIRST 32

/* One section's values as read. */
typedef struct parm_sec {
    int present;
    size_t n, cap;
    char (*text)[5]; /* 'a': 4 characters each */
    double *num;     /* 'I' and 'E' */
} parm_sec;

typedef struct parm_reader {
    ms_lines in;
    int old_style;
    char title[96];
    long ptr[P_NOLD];
    parm_sec sec[NSECS];
} parm_reader;

/* A Fortran format "(20a4)" "(5E16.8)" "(10I8)": per line and field width. */
static int parse_format(const char *s, int *per_line, int *width, char *kind)
{
    const char *p = strchr(s, '(');
    if (!p) return -1;
    char *end;
    long n = strtol(p + 1, &end, 10), w;
    if (n < 1 || n > 1000) return -1;
    *kind = (char)(*end >= 'a' && *end <= 'z' ? *end - 32 : *end);
    if (*kind != 'A' && *kind != 'I' && *kind != 'E' && *kind != 'F') return -1;
    w = strtol(end + 1, NULL, 10);
    if (w < 1 || w > 80) return -1;
    *per_line = (int)n;
    *width = (int)w;
    return 0;
}

static int sec_push(parm_sec *s, char kind)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 256;
        void *p = kind == 'a' ? realloc(s->text, cap * sizeof *s->text)
                              : realloc(s->num, cap * sizeof *s->num);
        if (!p) return -1;
        if (kind == 'a') s->text = p;
        else s->num = p;
        s->cap = cap;
    }
    s->n++;
    return 0;
}

/* The fields of one data line into section k (stored when the section is kept, else
 * counted). want: the most values to take from the line. */
static int read_fields(parm_reader *r, size_t k, int per_line, int width, ms_perr *err)
{
    const parm_sec_def *d = &parm_secs[k];
    parm_sec *s = &r->sec[k];
    const char *l = r->in.line;
    size_t len = r->in.line_len;
    while (len && (l[len - 1] == ' ' || l[len - 1] == '\r')) len--;
    for (int f = 0; f < per_line && (size_t)f * (size_t)width < len; f++) {
        size_t c0 = (size_t)f * (size_t)width;
        if (!d->keep) {
            s->n++;
            continue;
        }
        if (sec_push(s, d->kind)) return ms_perr_set(err, "out of memory in %s", d->flag);
        if (d->kind == 'a') {
            ms_field(l, len, c0, c0 + (size_t)(width < 4 ? width : 4), s->text[s->n - 1]);
            continue;
        }
        char tok[96];
        ms_field(l, len, c0, c0 + (size_t)width, tok);
        double v;
        if (!tok[0] || ms_parse_double(tok, strlen(tok), &v) < 0 ||
            (d->kind == 'I' && v != floor(v)))
            return ms_perr_set(err, "line %ld: bad value '%s' in %s", r->in.line_no, tok, d->flag);
        s->num[s->n - 1] = v;
    }
    return MS_PLUGIN_OK;
}

static int find_sec(const char *flag)
{
    for (size_t k = 0; k < NSECS; k++)
        if (!strcmp(parm_secs[k].flag, flag)) return (int)k;
    return -1;
}

/* ---------------------------------------------------------------- new format */

static int read_pointers_new(parm_reader *r, int per_line, int width, ms_perr *err)
{
    size_t got = 0;
    const char *l;
    long long at = ms_lines_tell_next(&r->in);
    long line_no = r->in.line_no;
    while ((l = ms_lines_next(&r->in)) && l[0] != '%') {
        for (int f = 0; f < per_line && got < P_NOLD; f++) {
            char tok[96];
            ms_field(l, r->in.line_len, (size_t)(f * width), (size_t)((f + 1) * width), tok);
            if (!tok[0]) break;
            if (ms_parse_long(tok, strlen(tok), &r->ptr[got]) < 0 || r->ptr[got] < 0)
                return ms_perr_set(err, "line %ld: bad POINTERS value '%s'", r->in.line_no, tok);
            got++;
        }
        at = ms_lines_tell_next(&r->in);
        line_no = r->in.line_no;
    }
    if (got < P_NOLD)
        return ms_perr_set(err, "POINTERS has %zu values, expected at least %d", got, P_NOLD);
    return l ? ms_lines_seek(&r->in, at, line_no) : 0;
}

/* The data lines of one "%FLAG" section, up to the next line starting with '%'. The
 * reader is left before that line. */
static int read_section_new(parm_reader *r, const char *flag, ms_perr *err)
{
    const char *l = ms_lines_next(&r->in);
    while (l && !strncmp(l, "%COMMENT", 8)) l = ms_lines_next(&r->in);
    int per_line, width;
    char kind;
    if (!l || strncmp(l, "%FORMAT", 7) || parse_format(l + 7, &per_line, &width, &kind))
        return ms_perr_set(err, "line %ld: %%FLAG %s is not followed by a %%FORMAT(...) line",
                           r->in.line_no, flag);
    if (!strcmp(flag, "POINTERS")) return read_pointers_new(r, per_line, width, err);
    int k = find_sec(flag), is_title = !strcmp(flag, "TITLE") || !strcmp(flag, "CTITLE");
    if (k >= 0) {
        const parm_sec_def *d = &parm_secs[k];
        if ((d->kind == 'a') != (kind == 'A'))
            return ms_perr_set(err, "line %ld: %%FLAG %s has format %c, not %s", r->in.line_no,
                               flag, kind, d->kind == 'a' ? "text" : "numbers");
        if (r->sec[k].present)
            return ms_perr_set(err, "line %ld: %%FLAG %s appears twice", r->in.line_no, flag);
        r->sec[k].present = 1;
    }
    for (;;) {
        long long at = ms_lines_tell_next(&r->in);
        long line_no = r->in.line_no;
        if (!(l = ms_lines_next(&r->in))) break;
        if (l[0] == '%') return ms_lines_seek(&r->in, at, line_no);
        if (is_title && !r->title[0]) snprintf(r->title, sizeof r->title, "%.80s", l);
        if (k >= 0 && read_fields(r, (size_t)k, per_line, width, err)) return MS_PLUGIN_ERROR;
    }
    return r->in.error ? ms_perr_set(err, "read error after line %ld", r->in.line_no) : 0;
}

static int read_new_style(parm_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    const char *l;
    int have_ptr = 0;
    while ((l = ms_lines_next(&r->in))) {
        if (strncmp(l, "%FLAG", 5)) continue; /* %VERSION, stray text */
        char flag[64];
        ms_field(l, r->in.line_len, 5, 64, flag);
        if (!flag[0]) return ms_perr_set(err, "line %ld: %%FLAG without a name", r->in.line_no);
        have_ptr |= !strcmp(flag, "POINTERS");
        if (read_section_new(r, flag, err)) return MS_PLUGIN_ERROR;
    }
    if (r->in.error) return ms_perr_set(err, "read error after line %ld", r->in.line_no);
    if (!have_ptr) return ms_perr_set(err, "no %%FLAG POINTERS section");
    if (r->title[0] && sink->add_remark(sink, r->title)) return ms_perr_set(err, "out of memory");
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- old format */

/* How many values section k holds according to the pointers. */
static double expected_count(const parm_reader *r, size_t k)
{
    const parm_sec_def *d = &parm_secs[k];
    double nt = (double)r->ptr[P_NTYPES];
    switch (d->count_rule) {
    case C_SQUARE: return nt * nt;
    case C_TRIANGLE: return nt * (nt + 1) / 2;
    case C_FIXED: return d->mult;
    case C_NSPM: {
        const parm_sec *sp = &r->sec[find_sec("SOLVENT_POINTERS")];
        return sp->n >= 2 ? sp->num[1] : 0;
    }
    default: return (double)d->mult * (double)r->ptr[d->ptr];
    }
}

/* One section of an old file: its values on ceil(n / per line) lines in its fixed format
 * (an empty section may be one blank line). */
static int read_section_old(parm_reader *r, size_t k, ms_perr *err)
{
    const parm_sec_def *d = &parm_secs[k];
    int per_line = d->kind == 'a' ? 20 : d->kind == 'I' ? 12 : 5;
    int width = d->kind == 'a' ? 4 : d->kind == 'I' ? 6 : 16;
    double want = expected_count(r, k);
    if (ms_check_room(err, want, (double)width, ms_lines_left(&r->in), "values",
                      "line %ld: the pointers declare %.0f values of %s", r->in.line_no, want,
                      d->flag))
        return MS_PLUGIN_ERROR;
    parm_sec *s = &r->sec[k];
    s->present = 1;
    if (want == 0) {
        long long at = ms_lines_tell_next(&r->in);
        long line_no = r->in.line_no;
        const char *l = ms_lines_next(&r->in);
        if (l && l[strspn(l, " \t\r")] != '\0') return ms_lines_seek(&r->in, at, line_no);
        return MS_PLUGIN_OK;
    }
    while ((double)s->n < want) {
        size_t before = s->n;
        if (!ms_lines_next(&r->in))
            return ms_perr_set(err, "%s: the file ends after %zu of %.0f values (line %ld)",
                               d->flag, s->n, want, r->in.line_no);
        int room = (int)fmin((double)per_line, want - (double)s->n);
        if (read_fields(r, k, room, width, err)) return MS_PLUGIN_ERROR;
        if (s->n == before)
            return ms_perr_set(err, "line %ld: %s: a blank line after %zu of %.0f values",
                               r->in.line_no, d->flag, s->n, want);
    }
    return MS_PLUGIN_OK;
}

static int read_old_style(parm_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    if (sink->add_remark(sink, r->title)) return ms_perr_set(err, "out of memory");
    int got = 0;
    while (got < P_NOLD) {
        const char *l = ms_lines_next(&r->in);
        if (!l)
            return ms_perr_set(err, "the file ends inside the pointers (line %ld)",
                               r->in.line_no);
        for (int f = 0; f < 12 && got < P_NOLD; f++) {
            char tok[16];
            ms_field(l, r->in.line_len, (size_t)(6 * f), (size_t)(6 * f + 6), tok);
            if (!tok[0]) break;
            if (ms_parse_long(tok, strlen(tok), &r->ptr[got]) < 0 || r->ptr[got] < 0)
                return ms_perr_set(err, "line %ld: bad pointer '%s' (not an AMBER topology?)",
                                   r->in.line_no, tok);
            got++;
        }
    }
    size_t last = r->ptr[P_IFBOX] > 0 ? NSECS - 1 : NOLD_SECS;
    for (size_t k = 0; k < last; k++)
        if (read_section_old(r, k, err)) return MS_PLUGIN_ERROR;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- building */

static const parm_sec *sec_named(const parm_reader *r, const char *flag)
{
    return &r->sec[find_sec(flag)];
}

/* Every kept section is present (those the file may lack excepted) with the count the
 * pointers give. */
static int check_counts(parm_reader *r, ms_perr *err)
{
    if (r->ptr[P_NATOM] == 0) return ms_perr_set(err, "POINTERS says 0 atoms");
    for (size_t k = 0; k < NSECS; k++) {
        const parm_sec_def *d = &parm_secs[k];
        const parm_sec *s = &r->sec[k];
        int optional = k >= S_BOX_FIRST;
        if (!d->keep || (!s->present && optional)) continue;
        if (d->count_rule == C_FIXED && k != (size_t)find_sec("BOX_DIMENSIONS")) continue;
        double want = expected_count(r, k);
        if (!s->present)
            return ms_perr_set(err, "no %%FLAG %s section (POINTERS expects %.0f values)",
                               d->flag, want);
        if ((double)s->n != want)
            return ms_perr_set(err, "%s has %zu values but POINTERS says %.0f", d->flag, s->n,
                               want);
    }
    return MS_PLUGIN_OK;
}

static int add_atoms(parm_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    const parm_sec *name = sec_named(r, "ATOM_NAME"), *charge = sec_named(r, "CHARGE"),
                   *mass = sec_named(r, "MASS"), *type = sec_named(r, "AMBER_ATOM_TYPE"),
                   *rlab = sec_named(r, "RESIDUE_LABEL"), *rptr = sec_named(r, "RESIDUE_POINTER"),
                   *anum = sec_named(r, "ATOMIC_NUMBER");
    long natoms = r->ptr[P_NATOM], nres = r->ptr[P_NRES];
    if (nres < 1 || rptr->num[0] != 1)
        return ms_perr_set(err, "RESIDUE_POINTER does not start at atom 1");
    sink->reserve(sink, (size_t)natoms);
    long res = 0;
    for (long i = 0; i < natoms; i++) {
        while (res + 1 < nres && rptr->num[res + 1] <= (double)(i + 1)) {
            if (rptr->num[res + 1] <= rptr->num[res])
                return ms_perr_set(err, "RESIDUE_POINTER %ld (%.0f) is not after the one before",
                                   res + 2, rptr->num[res + 1]);
            res++;
        }
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        a.name = name->text[i];
        a.type = type->text[i];
        a.resname = rlab->text[res];
        a.resid = (int)res + 1;
        a.charge = (float)(charge->num[i] / AMBER_CHARGE_UNIT);
        a.mass = (float)mass->num[i];
        a.has = MS_HAS_CHARGE | MS_HAS_MASS;
        if (anum->present && anum->num[i] > 0 && anum->num[i] < 200) {
            a.atomicnumber = (int)anum->num[i];
            a.has |= MS_HAS_ATOMICNUMBER;
        }
        a.altloc = a.insertion = ' ';
        if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory at atom %ld", i + 1);
    }
    if (res + 1 != nres)
        return ms_perr_set(err, "RESIDUE_POINTER: residue %ld starts after the last atom", res + 2);
    return MS_PLUGIN_OK;
}

/* The atom of a coordinate index (3 (atom - 1), negative for a flag), or -1 when bad. */
static long atom_of(double v, long natoms)
{
    double a = fabs(v);
    if (fmod(a, 3.0) != 0 || a / 3 >= (double)natoms) return -1;
    return (long)(a / 3);
}

/* A quartet of a dihedral seen before: the extra Fourier terms repeat the atoms. */
typedef struct quad_set {
    size_t cap;
    size_t (*slot)[4];
    unsigned char *used;
} quad_set;

static int quad_seen(quad_set *q, const size_t at[4])
{
    size_t h = 1469598103934665603u;
    for (int k = 0; k < 4; k++) h = (h ^ at[k]) * 1099511628211u;
    for (size_t i = h & (q->cap - 1);; i = (i + 1) & (q->cap - 1)) {
        if (!q->used[i]) {
            q->used[i] = 1;
            memcpy(q->slot[i], at, sizeof q->slot[i]);
            return 0;
        }
        if (!memcmp(q->slot[i], at, sizeof q->slot[i])) return 1;
    }
}

/* One bond, angle or dihedral record (width values, the last a parameter index). */
static int add_record(ms_struct_sink *sink, const double *v, int width, long natoms,
                      quad_set *seen)
{
    size_t at[4];
    for (int q = 0; q < width - 1; q++) {
        long a = atom_of(v[q], natoms);
        if (a < 0 || (q < 2 && v[q] < 0)) return 1;
        at[q] = (size_t)a;
    }
    if (width == 3) return sink->add_bond(sink, at[0], at[1], 1.0f) ? -1 : 0;
    if (width == 4) return sink->add_term(sink, MS_PTERM_ANGLE, at, NULL) ? -1 : 0;
    if (v[3] < 0) return sink->add_term(sink, MS_PTERM_IMPROPER, at, NULL) ? -1 : 0;
    if (quad_seen(seen, at)) return 0;
    return sink->add_term(sink, MS_PTERM_DIHEDRAL, at, NULL) ? -1 : 0;
}

static int add_section_records(parm_reader *r, ms_struct_sink *sink, const char *flag,
                               quad_set *seen, ms_perr *err)
{
    const parm_sec_def *d = &parm_secs[find_sec(flag)];
    const parm_sec *s = sec_named(r, flag);
    for (size_t i = 0; i + (size_t)d->mult <= s->n; i += (size_t)d->mult) {
        int rc = add_record(sink, s->num + i, d->mult, r->ptr[P_NATOM], seen);
        if (rc < 0) return ms_perr_set(err, "out of memory in %s", flag);
        if (rc > 0)
            return ms_perr_set(err, "%s record %zu names atom index %.0f, not one of %ld atoms",
                               flag, i / (size_t)d->mult + 1, s->num[i], r->ptr[P_NATOM]);
    }
    return MS_PLUGIN_OK;
}

static int add_connectivity(parm_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    static const char *const flags[] = {
        "BONDS_INC_HYDROGEN", "BONDS_WITHOUT_HYDROGEN", "ANGLES_INC_HYDROGEN",
        "ANGLES_WITHOUT_HYDROGEN", "DIHEDRALS_INC_HYDROGEN", "DIHEDRALS_WITHOUT_HYDROGEN"};
    quad_set seen = {0, NULL, NULL};
    size_t nd = (size_t)(r->ptr[P_NPHIH] + r->ptr[P_MPHIA]);
    for (seen.cap = 16; seen.cap < 2 * nd; seen.cap *= 2)
        ;
    seen.slot = malloc(seen.cap * sizeof *seen.slot);
    seen.used = calloc(seen.cap, 1);
    int rc = MS_PLUGIN_OK;
    if (!seen.slot || !seen.used) rc = ms_perr_set(err, "out of memory for %zu dihedrals", nd);
    for (size_t k = 0; k < 6 && rc == MS_PLUGIN_OK; k++) {
        rc = add_section_records(r, sink, flags[k], &seen, err);
        if (k == 1 && rc == MS_PLUGIN_OK) sink->bonds_complete(sink);
    }
    free(seen.slot);
    free(seen.used);
    return rc;
}

/* The box of IFBOX > 0: BOX_DIMENSIONS is beta and the three lengths. A truncated
 * octahedron (IFBOX 2) has all three angles equal to beta. */
static void set_box(parm_reader *r, ms_struct_sink *sink)
{
    const parm_sec *b = sec_named(r, "BOX_DIMENSIONS");
    if (r->ptr[P_IFBOX] <= 0 || !b->present || b->n < 4) return;
    double beta = b->num[0];
    int octa = r->ptr[P_IFBOX] == 2 || fabs(beta - 109.4712190) < 1e-3;
    float cell[6] = {(float)b->num[1], (float)b->num[2], (float)b->num[3],
                     (float)(octa ? beta : 90.0), (float)beta, (float)(octa ? beta : 90.0)};
    sink->set_cell(sink, cell);
}

static int parm_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    parm_reader *r = h;
    if ((r->old_style ? read_old_style(r, sink, err) : read_new_style(r, sink, err)) ||
        check_counts(r, err) || add_atoms(r, sink, err) || add_connectivity(r, sink, err))
        return MS_PLUGIN_ERROR;
    set_box(r, sink);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- open and close */

static void parm_close_read(void *h)
{
    parm_reader *r = h;
    if (!r) return;
    for (size_t k = 0; k < NSECS; k++) {
        free(r->sec[k].text);
        free(r->sec[k].num);
    }
    ms_lines_destroy(r);
}

/* Does an old file's second line look like pointers: at least 10 six-column integers? */
static int looks_like_pointers(const char *l, size_t len)
{
    int n = 0;
    for (size_t c = 0; c + 6 <= len && n < 12; c += 6, n++) {
        int v;
        if (ms_field_int(l, len, c, c + 6, &v) != 1 || v < 0) return 0;
    }
    return n >= 10;
}

static void *parm_open_read(const char *path, long *natoms, ms_perr *err)
{
    parm_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    const char *l = ms_lines_next(&r->in);
    *natoms = -1;
    if (l && (!strncmp(l, "%VERSION", 8) || !strncmp(l, "%FLAG", 5))) {
        if (ms_lines_seek(&r->in, 0, 0) == 0) return r;
    } else if (l) {
        snprintf(r->title, sizeof r->title, "%.80s", l);
        long long at = ms_lines_tell_next(&r->in);
        const char *p = ms_lines_next(&r->in);
        if (p && looks_like_pointers(p, r->in.line_len) && ms_lines_seek(&r->in, at, 1) == 0) {
            r->old_style = 1;
            return r;
        }
    }
    parm_close_read(r);
    ms_perr_set(err, "line 1: not an AMBER topology (no %%VERSION or %%FLAG header, and no "
                     "title line followed by pointers)");
    return NULL;
}

static const ms_plugin parm_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = PARM_TYPE_NAME,
    .description = PARM_DESCRIPTION,
    .extensions = PARM_EXTENSIONS,
    .caps = MS_CAN_READ_STRUCTURE,
    .open_read = parm_open_read,
    .read_structure = parm_read_structure,
    .close_read = parm_close_read,
};

const ms_plugin *ms_plugin_entry(void) { return &parm_plugin; }
