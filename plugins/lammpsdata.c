/* lammpsdata.c: the LAMMPS data file plugin (VMD's type name `lammpsdata`). Reads the header
 * (counts, type counts, xlo xhi ... and the tilt factors xy xz yz), Masses, the Atoms of
 * the atom styles atomic, charge, bond, angle, molecular and full (the style from the
 * caller's atom_style option, else the "Atoms # style" comment, else the column count),
 * image flags (applied to the coordinates, as VMD's topotools does), Velocities, Bonds,
 * Angles, Dihedrals and Impropers with their types, and the type labels (the *Type Labels
 * sections and "# name" comments); coefficient and body sections are skipped. Atoms come
 * out in the order of their ids. Writes one frame in any of those styles (atom_style
 * option, default full), numbering types as the file-independent names ask. */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "lammps_util.h"

#include <stdlib.h>
#include <string.h>

enum { K_ATOM, K_BOND, K_ANGLE, K_DIHEDRAL, K_IMPROPER, K_KINDS };

/* Type tables have an entry a type: the header's type counts are bounded. */
#define MAX_TYPES (1 << 20)

/* The atom styles: the columns of an Atoms line (-1: absent). */
typedef struct data_style {
    const char *name;
    int ncols, mol, type, q, x;
} data_style;

static const data_style data_styles[] = {
    {"atomic", 5, -1, 1, -1, 2},  {"charge", 6, -1, 1, 2, 3}, {"bond", 6, 1, 2, -1, 3},
    {"angle", 6, 1, 2, -1, 3},    {"molecular", 6, 1, 2, -1, 3}, {"full", 7, 1, 2, 3, 4},
    {NULL, 0, 0, 0, 0, 0}};

static const data_style *style_named(const char *name)
{
    for (const data_style *s = data_styles; s->name; s++)
        if (!strcmp(s->name, name)) return s;
    return NULL;
}

typedef struct data_atom {
    long id, mol, type;
    float q, x, y, z;
    int img[3];
    long line;
} data_atom;

typedef struct data_vel {
    long id;
    float v[3];
} data_vel;

/* Bonds (K_BOND) and terms: per record its type and its atoms' ids, width + 1 longs. */
typedef struct data_records {
    long *v;
    size_t n, cap;
} data_records;

typedef struct data_reader {
    ms_lines in;
    long count[K_KINDS];   /* atoms, bonds, angles, dihedrals, impropers */
    long ntypes[K_KINDS];  /* atom, bond ... improper types */
    ms_lmp_box box;
    int have_box[3];
    const data_style *style;
    char title[256];
    data_atom *atoms;
    size_t natoms;
    data_vel *vel;
    size_t nvel, vcap;
    char atoms_comment[64]; /* "full" of "Atoms # full" */
    double *mass;          /* ntypes[K_ATOM] + 1, NaN when not given; NULL: no Masses */
    char **labels[K_KINDS];/* ntypes[k] + 1 names, NULL when none */
    data_records rec[K_KINDS]; /* rec[K_ATOM] unused */
} data_reader;

static const char *const kind_word[K_KINDS] = {"atom", "bond", "angle", "dihedral", "improper"};
static const char *const count_word[K_KINDS] = {"atoms", "bonds", "angles", "dihedrals",
                                                "impropers"};
static const char *const section_of[K_KINDS] = {"Atoms", "Bonds", "Angles", "Dihedrals",
                                                "Impropers"};
static const int term_width[K_KINDS] = {1, 2, 3, 4, 4};

static void *data_open_read(const char *path, long *natoms, ms_perr *err)
{
    data_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void data_close_read(void *h)
{
    data_reader *r = h;
    free(r->atoms);
    free(r->vel);
    free(r->mass);
    for (int k = 0; k < K_KINDS; k++) {
        for (long t = 0; r->labels[k] && t <= r->ntypes[k]; t++) free(r->labels[k][t]);
        free(r->labels[k]);
        free(r->rec[k].v);
    }
    ms_lines_destroy(r);
}

/* Split a line at its comment: the tokens before '#' (at most max) and the comment's text
 * (trimmed, "" when none). line is modified. */
static int split_line(char *line, char **tok, int max, const char **comment)
{
    char *hash = strchr(line, '#');
    *comment = "";
    if (hash) {
        *hash = '\0';
        char *c = hash + 1 + strspn(hash + 1, " \t");
        size_t n = strlen(c);
        while (n && (c[n - 1] == ' ' || c[n - 1] == '\t' || c[n - 1] == '\r')) c[--n] = '\0';
        *comment = c;
    }
    return ms_tokens(line, tok, max);
}

/* Room for `need` elements in *p (capacity *cap); 0 or -1. */
static int grow(void **p, size_t *cap, size_t need, size_t elsize)
{
    if (need <= *cap) return 0;
    size_t n = *cap ? *cap : 64;
    while (n < need) n *= 2;
    void *q = realloc(*p, n * elsize);
    if (!q) return -1;
    *p = q;
    *cap = n;
    return 0;
}

static int parse_long_tok(const char *s, long *v) { return ms_parse_long(s, strlen(s), v) > 0; }
static int parse_double_tok(const char *s, double *v)
{
    return ms_parse_double(s, strlen(s), v) > 0;
}

/* ---------------------------------------------------------------- header */

/* One header line (tokens tok[0..nt)); 0 when understood, 1 when it is no header line. */
static int header_line(data_reader *r, char **tok, int nt, ms_perr *err)
{
    long n;
    ms_lines *in = &r->in;
    static const char *const axes[3][2] = {{"xlo", "xhi"}, {"ylo", "yhi"}, {"zlo", "zhi"}};
    for (int d = 0; d < 3; d++)
        if (nt == 4 && !strcmp(tok[2], axes[d][0]) && !strcmp(tok[3], axes[d][1])) {
            if (!parse_double_tok(tok[0], &r->box.lo[d]) || !parse_double_tok(tok[1], &r->box.hi[d]))
                return ms_perr_set(err, "line %ld: bad %s %s values", in->line_no, tok[2], tok[3]);
            r->have_box[d] = 1;
            return 0;
        }
    if (nt == 6 && !strcmp(tok[3], "xy") && !strcmp(tok[4], "xz") && !strcmp(tok[5], "yz")) {
        if (!parse_double_tok(tok[0], &r->box.xy) || !parse_double_tok(tok[1], &r->box.xz) ||
            !parse_double_tok(tok[2], &r->box.yz))
            return ms_perr_set(err, "line %ld: bad tilt factors", in->line_no);
        r->box.triclinic = 1;
        return 0;
    }
    if (nt < 2 || !parse_long_tok(tok[0], &n)) return 1;
    for (int k = 0; k < K_KINDS; k++) {
        long *dst = NULL;
        if (nt == 2 && !strcmp(tok[1], count_word[k])) dst = &r->count[k];
        if (nt == 3 && !strcmp(tok[1], kind_word[k]) && !strcmp(tok[2], "types"))
            dst = &r->ntypes[k];
        if (!dst) continue;
        if (n < 0 || n > 2000000000L)
            return ms_perr_set(err, "line %ld: bad count %ld of %s", in->line_no, n, tok[1]);
        if (dst == &r->ntypes[k] && n > MAX_TYPES)
            return ms_perr_set(err, "line %ld: %ld %s types: molscope reads at most %d",
                               in->line_no, n, kind_word[k], MAX_TYPES);
        *dst = n;
        return 0;
    }
    return 0; /* "N extra bond per atom", "N ellipsoids" ...: not needed */
}

/* ---------------------------------------------------------------- sections */

enum { S_NONE, S_ATOMS, S_VELOCITIES, S_MASSES, S_BONDS, S_ANGLES, S_DIHEDRALS, S_IMPROPERS,
       S_LABELS, S_SKIP };

/* Which section a (comment-stripped, trimmed) line names; *kind for term and label
 * sections. */
static int section_kind(const char *s, int *kind)
{
    static const char *const labels[K_KINDS] = {"Atom Type Labels", "Bond Type Labels",
                                                "Angle Type Labels", "Dihedral Type Labels",
                                                "Improper Type Labels"};
    static const char *const skipped[] = {"Ellipsoids", "Lines", "Triangles", "Bodies", NULL};
    *kind = K_ATOM;
    if (!strcmp(s, "Atoms")) return S_ATOMS;
    if (!strcmp(s, "Velocities")) return S_VELOCITIES;
    if (!strcmp(s, "Masses")) return S_MASSES;
    for (int k = K_BOND; k < K_KINDS; k++)
        if (!strcmp(s, section_of[k])) {
            *kind = k;
            return S_BONDS + k - K_BOND;
        }
    for (int k = 0; k < K_KINDS; k++)
        if (!strcmp(s, labels[k])) {
            *kind = k;
            return S_LABELS;
        }
    for (int k = 0; skipped[k]; k++)
        if (!strcmp(s, skipped[k])) return S_SKIP;
    size_t n = strlen(s);
    if (n > 7 && !strcmp(s + n - 7, " Coeffs")) return S_SKIP;
    return S_NONE;
}

/* The trimmed text of a line before any comment, in buf. */
static const char *bare(const char *line, char *buf, size_t n)
{
    snprintf(buf, n, "%s", line + strspn(line, " \t"));
    char *hash = strchr(buf, '#');
    if (hash) *hash = '\0';
    size_t len = strlen(buf);
    while (len && strchr(" \t\r", buf[len - 1])) buf[--len] = '\0';
    return buf;
}

/* A type named by a token: a number in 1..ntypes, or a label of that kind. -1 when
 * neither. */
static long type_of(const data_reader *r, int kind, const char *tok)
{
    long t;
    if (parse_long_tok(tok, &t)) return t >= 1 && t <= r->ntypes[kind] ? t : -1;
    for (long k = 1; r->labels[kind] && k <= r->ntypes[kind]; k++)
        if (r->labels[kind][k] && !strcmp(r->labels[kind][k], tok)) return k;
    return -1;
}

/* Name type t of a kind (when it has none yet). */
static int set_label(data_reader *r, int kind, long t, const char *name, int replace)
{
    if (!*name) return 0;
    if (!r->labels[kind] && !(r->labels[kind] = calloc((size_t)r->ntypes[kind] + 1, sizeof(char *))))
        return -1;
    if (r->labels[kind][t] && !replace) return 0;
    char *copy = malloc(strlen(name) + 1);
    if (!copy) return -1;
    strcpy(copy, name);
    free(r->labels[kind][t]);
    r->labels[kind][t] = copy;
    return 0;
}

/* The style of the Atoms section: the caller's option, the section's comment, or the
 * column count of its first line. */
static int pick_style(data_reader *r, const char *comment, int nt, const char *opt,
                      ms_perr *err)
{
    char want[64] = "";
    if (opt && ms_lmp_option(opt, "atom_style", want, sizeof want) && want[0]) {
    } else if (*comment) {
        snprintf(want, sizeof want, "%s", comment);
        want[strcspn(want, " \t")] = '\0';
    }
    if (want[0]) {
        if (!(r->style = style_named(want)))
            return ms_perr_set(err, "line %ld: unsupported atom style '%.40s' (molscope reads "
                               "atomic, bond, angle, molecular, charge and full)",
                               r->in.line_no, want);
        return MS_PLUGIN_OK;
    }
    int n = nt > 7 ? nt - 3 : nt;
    r->style = n == 5 ? style_named("atomic")
             : n == 7 ? style_named("full")
             : n == 6 ? style_named(r->count[K_BOND] > 0 ? "molecular" : "charge")
                      : NULL;
    if (!r->style)
        return ms_perr_set(err, "line %ld: cannot tell the atom style from %d columns; give it "
                           "(Atoms # full)", r->in.line_no, nt);
    return MS_PLUGIN_OK;
}

static int atom_line(data_reader *r, char **tok, int nt, data_atom *a, ms_perr *err)
{
    const data_style *s = r->style;
    long line = r->in.line_no;
    if (nt != s->ncols && nt != s->ncols + 3)
        return ms_perr_set(err, "line %ld: atom style %s needs %d or %d columns, found %d", line,
                           s->name, s->ncols, s->ncols + 3, nt);
    memset(a, 0, sizeof *a);
    a->line = line;
    if (!parse_long_tok(tok[0], &a->id) || a->id < 1)
        return ms_perr_set(err, "line %ld: bad atom id '%.32s'", line, tok[0]);
    if (s->mol >= 0 && !parse_long_tok(tok[s->mol], &a->mol))
        return ms_perr_set(err, "line %ld: bad molecule id '%.32s'", line, tok[s->mol]);
    if ((a->type = type_of(r, K_ATOM, tok[s->type])) < 0)
        return ms_perr_set(err, "line %ld: bad atom type '%.32s' (%ld atom types)", line,
                           tok[s->type], r->ntypes[K_ATOM]);
    if (s->q >= 0 && ms_parse_float(tok[s->q], strlen(tok[s->q]), &a->q) < 0)
        return ms_perr_set(err, "line %ld: bad charge '%.32s'", line, tok[s->q]);
    float *xyz[3] = {&a->x, &a->y, &a->z};
    for (int d = 0; d < 3; d++)
        if (ms_parse_float(tok[s->x + d], strlen(tok[s->x + d]), xyz[d]) < 0)
            return ms_perr_set(err, "line %ld: bad coordinate '%.32s'", line, tok[s->x + d]);
    for (int d = 0; nt > s->ncols && d < 3; d++) {
        long v;
        if (!parse_long_tok(tok[s->ncols + d], &v) || v < -1000000 || v > 1000000)
            return ms_perr_set(err, "line %ld: bad image flag '%.32s'", line, tok[s->ncols + d]);
        a->img[d] = (int)v;
    }
    return MS_PLUGIN_OK;
}

/* A record of a term section: "id type atom atom ...". */
static int term_line(data_reader *r, int kind, char **tok, int nt, const char *comment,
                     ms_perr *err)
{
    int w = term_width[kind];
    long line = r->in.line_no;
    if (nt != w + 2)
        return ms_perr_set(err, "line %ld: a %s needs %d columns (id type and %d atoms), found "
                           "%d", line, kind_word[kind], w + 2, w, nt);
    data_records *rc = &r->rec[kind];
    if (grow((void **)&rc->v, &rc->cap, (rc->n + 1) * (size_t)(w + 1), sizeof *rc->v))
        return ms_perr_set(err, "out of memory at line %ld", line);
    long *v = rc->v + rc->n * (size_t)(w + 1);
    if ((v[0] = type_of(r, kind, tok[1])) < 0)
        return ms_perr_set(err, "line %ld: bad %s type '%.32s' (%ld %s types)", line,
                           kind_word[kind], tok[1], r->ntypes[kind], kind_word[kind]);
    for (int q = 0; q < w; q++)
        if (!parse_long_tok(tok[2 + q], &v[1 + q]) || v[1 + q] < 1)
            return ms_perr_set(err, "line %ld: bad atom id '%.32s'", line, tok[2 + q]);
    if (set_label(r, kind, v[0], comment, 0)) return ms_perr_set(err, "out of memory");
    rc->n++;
    return MS_PLUGIN_OK;
}

static int mass_line(data_reader *r, char **tok, int nt, const char *comment, ms_perr *err)
{
    long t;
    double m;
    if (nt != 2 || (t = type_of(r, K_ATOM, tok[0])) < 0 || !parse_double_tok(tok[1], &m))
        return ms_perr_set(err, "line %ld: expected 'type mass' with a type from 1 to %ld",
                           r->in.line_no, r->ntypes[K_ATOM]);
    r->mass[t] = m;
    return set_label(r, K_ATOM, t, comment, 0) ? ms_perr_set(err, "out of memory") : 0;
}

static int velocity_line(data_reader *r, char **tok, int nt, ms_perr *err)
{
    data_vel v;
    if (nt < 4 || !parse_long_tok(tok[0], &v.id))
        return ms_perr_set(err, "line %ld: expected 'id vx vy vz'", r->in.line_no);
    for (int d = 0; d < 3; d++)
        if (ms_parse_float(tok[1 + d], strlen(tok[1 + d]), &v.v[d]) < 0)
            return ms_perr_set(err, "line %ld: bad velocity '%.32s'", r->in.line_no, tok[1 + d]);
    if (grow((void **)&r->vel, &r->vcap, r->nvel + 1, sizeof *r->vel))
        return ms_perr_set(err, "out of memory");
    r->vel[r->nvel++] = v;
    return MS_PLUGIN_OK;
}

static int label_line(data_reader *r, int kind, char **tok, int nt, ms_perr *err)
{
    long t;
    if (nt != 2 || !parse_long_tok(tok[0], &t) || t < 1 || t > r->ntypes[kind])
        return ms_perr_set(err, "line %ld: expected 'type label' with a type from 1 to %ld",
                           r->in.line_no, r->ntypes[kind]);
    return set_label(r, kind, t, tok[1], 1) ? ms_perr_set(err, "out of memory") : 0;
}

/* How many lines a section holds, and whether the header allows it. */
static long section_lines(data_reader *r, int sec, int kind, ms_perr *err)
{
    long n = sec == S_ATOMS || sec == S_VELOCITIES ? r->count[K_ATOM]
           : sec == S_MASSES || sec == S_LABELS    ? r->ntypes[kind]
                                                   : r->count[kind];
    if (sec == S_ATOMS && r->atoms)
        return ms_perr_set(err, "line %ld: a second Atoms section", r->in.line_no);
    /* every record takes a few bytes: the file bounds the count */
    if (ms_check_room(err, (double)n, 6, ms_lines_left(&r->in), "records",
                      "line %ld: the header declares %ld lines for this section", r->in.line_no, n))
        return -1;
    return n;
}

/* One record of a section; the line's tokens and comment. */
static int section_record(data_reader *r, int sec, int kind, char *line, ms_perr *err)
{
    char *tok[16];
    const char *comment;
    int nt = split_line(line, tok, 16, &comment);
    switch (sec) {
    case S_ATOMS:
        return atom_line(r, tok, nt, &r->atoms[r->natoms++], err);
    case S_VELOCITIES:
        return velocity_line(r, tok, nt, err);
    case S_MASSES:
        return mass_line(r, tok, nt, comment, err);
    case S_LABELS:
        return label_line(r, kind, tok, nt, err);
    default:
        return term_line(r, kind, tok, nt, comment, err);
    }
}

/* The next line that is not blank, NULL at the end (in->error on a read error). */
static char *next_text(ms_lines *in)
{
    const char *l;
    while ((l = ms_lines_next(in))) {
        const char *p = l + strspn(l, " \t\r");
        if (*p && *p != '#') return in->line;
    }
    return NULL;
}

/* The n records of a section whose name line (with its comment) was just read. */
static int read_section(data_reader *r, int sec, int kind, const char *name,
                        const char *opt, ms_perr *err)
{
    long n = section_lines(r, sec, kind, err);
    if (n < 0) return MS_PLUGIN_ERROR;
    if (sec == S_ATOMS && !(r->atoms = calloc((size_t)n + 1, sizeof *r->atoms)))
        return ms_perr_set(err, "out of memory for %ld atoms", n);
    for (long k = 0; k < n; k++) {
        char *l = next_text(&r->in);
        if (!l)
            return ms_perr_set(err, "%s: the file ends after %ld of %ld lines (line %ld)",
                               name, k, n, r->in.line_no);
        if (sec == S_ATOMS && k == 0) {
            char copy[4096], *tok[16];
            const char *c;
            snprintf(copy, sizeof copy, "%s", l);
            int nt = split_line(copy, tok, 16, &c);
            if (pick_style(r, r->atoms_comment, nt, opt, err)) return MS_PLUGIN_ERROR;
        }
        if (section_record(r, sec, kind, l, err)) return MS_PLUGIN_ERROR;
    }
    return MS_PLUGIN_OK;
}

/* The header, then every section up to the end of the file. */
static int read_file(data_reader *r, const char *opt, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l = ms_lines_next(in);
    if (!l) return ms_perr_set(err, in->error ? "read error" : "empty file");
    snprintf(r->title, sizeof r->title, "%s", l);
    char buf[4096];
    int sec = S_NONE, kind = 0, in_header = 1, skipping = 0;
    char *line;
    while ((line = next_text(in))) {
        const char *name = bare(line, buf, sizeof buf);
        sec = section_kind(name, &kind);
        if (sec == S_NONE) {
            if (skipping) continue;
            if (!in_header)
                return ms_perr_set(err, "line %ld: expected a section name (Atoms, Bonds ...), "
                                   "found '%.40s'", in->line_no, name);
            char *tok[8];
            const char *c;
            int nt = split_line(line, tok, 8, &c);
            int rc = header_line(r, tok, nt, err);
            if (rc < 0) return MS_PLUGIN_ERROR;
            if (rc > 0)
                return ms_perr_set(err, "line %ld: not a LAMMPS data header line: '%.40s'",
                                   in->line_no, name);
            continue;
        }
        in_header = 0;
        if (sec == S_MASSES && !r->mass) {
            if (!(r->mass = malloc(((size_t)r->ntypes[K_ATOM] + 1) * sizeof *r->mass)))
                return ms_perr_set(err, "out of memory");
            for (long t = 0; t <= r->ntypes[K_ATOM]; t++) r->mass[t] = NAN;
        }
        skipping = sec == S_SKIP;
        if (skipping) continue;
        if (sec == S_ATOMS) {
            const char *hash = strchr(line, '#');
            snprintf(r->atoms_comment, sizeof r->atoms_comment, "%s",
                     hash ? hash + 1 + strspn(hash + 1, " \t") : "");
            r->atoms_comment[strcspn(r->atoms_comment, " \t\r")] = '\0';
        }
        char secname[64];
        snprintf(secname, sizeof secname, "%s", name);
        if (read_section(r, sec, kind, secname, opt, err)) return MS_PLUGIN_ERROR;
    }
    if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
    if (r->count[K_ATOM] == 0) return ms_perr_set(err, "the header declares no atoms");
    if (!r->atoms) return ms_perr_set(err, "no Atoms section");
    for (int k = K_BOND; k < K_KINDS; k++)
        if ((long)r->rec[k].n != r->count[k])
            return ms_perr_set(err, "the header declares %ld %s but the file has %zu",
                               r->count[k], count_word[k], r->rec[k].n);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- handing it over */

static int by_id(const void *a, const void *b)
{
    long x = ((const data_atom *)a)->id, y = ((const data_atom *)b)->id;
    return (x > y) - (x < y);
}

/* Index (in id order) of the atom with this id, -1 when none. */
static long index_of(const data_reader *r, long id)
{
    size_t lo = 0, hi = r->natoms;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (r->atoms[mid].id < id) lo = mid + 1;
        else hi = mid;
    }
    return lo < r->natoms && r->atoms[lo].id == id ? (long)lo : -1;
}

/* The name of type t of a kind: its label, else its number. */
static const char *type_name(const data_reader *r, int kind, long t, char buf[24])
{
    if (r->labels[kind] && r->labels[kind][t]) return r->labels[kind][t];
    snprintf(buf, 24, "%ld", t);
    return buf;
}

static int emit_atoms(data_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    qsort(r->atoms, r->natoms, sizeof *r->atoms, by_id);
    for (size_t i = 1; i < r->natoms; i++)
        if (r->atoms[i].id == r->atoms[i - 1].id)
            return ms_perr_set(err, "line %ld: atom id %ld appears twice", r->atoms[i].line,
                               r->atoms[i].id);
    float (*vel)[3] = r->nvel ? calloc(r->natoms, sizeof *vel) : NULL;
    if (r->nvel && !vel) return ms_perr_set(err, "out of memory");
    for (size_t k = 0; k < r->nvel; k++) {
        long i = index_of(r, r->vel[k].id);
        if (i >= 0) memcpy(vel[i], r->vel[k].v, sizeof vel[i]);
    }
    sink->reserve(sink, r->natoms);
    int rc = MS_PLUGIN_OK;
    for (size_t i = 0; i < r->natoms && rc == MS_PLUGIN_OK; i++) {
        const data_atom *d = &r->atoms[i];
        char tb[24];
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        a.name = a.type = type_name(r, K_ATOM, d->type, tb);
        a.resid = (int)d->mol;
        a.charge = d->q;
        a.has = MS_HAS_POS | (r->style->q >= 0 ? MS_HAS_CHARGE : 0);
        if (r->mass && !isnan(r->mass[d->type])) a.mass = (float)r->mass[d->type], a.has |= MS_HAS_MASS;
        double n[3] = {d->img[0], d->img[1], d->img[2]}, shift[3];
        ms_lmp_to_space(&r->box, n, 0, shift);
        a.x = (float)(d->x + shift[0]), a.y = (float)(d->y + shift[1]);
        a.z = (float)(d->z + shift[2]);
        if (vel) {
            a.vx = vel[i][0], a.vy = vel[i][1], a.vz = vel[i][2];
            a.has |= MS_HAS_VEL;
        }
        if (sink->add_atom(sink, &a)) rc = ms_perr_set(err, "out of memory");
    }
    free(vel);
    return rc;
}

static int emit_terms(data_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    for (int k = K_BOND; k < K_KINDS; k++) {
        int w = term_width[k];
        for (size_t q = 0; q < r->rec[k].n; q++) {
            const long *v = r->rec[k].v + q * (size_t)(w + 1);
            size_t at[4];
            for (int j = 0; j < w; j++) {
                long i = index_of(r, v[1 + j]);
                if (i < 0)
                    return ms_perr_set(err, "%s: %s %zu names atom %ld, which the Atoms section "
                                       "does not have", section_of[k], kind_word[k], q + 1,
                                       v[1 + j]);
                at[j] = (size_t)i;
            }
            char tb[24];
            const char *type = type_name(r, k, v[0], tb);
            int bad = k == K_BOND ? sink->add_typed_bond(sink, at[0], at[1], 1.0f, type)
                                  : sink->add_term(sink, k - K_ANGLE + MS_PTERM_ANGLE, at, type);
            if (bad) return ms_perr_set(err, "out of memory");
        }
        if (k == K_BOND) sink->bonds_complete(sink);
    }
    return MS_PLUGIN_OK;
}

static int data_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    data_reader *r = h;
    if (read_file(r, sink->options, err)) return MS_PLUGIN_ERROR;
    for (int d = 0; d < 3; d++)
        if (!r->have_box[d]) r->box.lo[d] = r->box.hi[d] = 0;
    float cell[6];
    if (ms_lmp_box_to_cell(&r->box, cell)) sink->set_cell(sink, cell);
    if (r->title[0] && sink->add_remark(sink, r->title)) return ms_perr_set(err, "out of memory");
    if (emit_atoms(r, sink, err)) return MS_PLUGIN_ERROR;
    return emit_terms(r, sink, err);
}

/* ---------------------------------------------------------------- writing */

/* Numbers for the type names of one kind: the names themselves when every one is a
 * positive integer (a data file read back keeps its numbers), else their rank in sorted
 * order, from 1. */
typedef struct type_map {
    const char **names;   /* sorted, unique */
    size_t n, cap;
    int numeric;
    long ntypes;
} type_map;

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static int map_add(type_map *m, const char *name)
{
    if (grow((void **)&m->names, &m->cap, m->n + 1, sizeof *m->names)) return -1;
    m->names[m->n++] = name ? name : "";
    return 0;
}

static void map_finish(type_map *m)
{
    if (m->n) qsort(m->names, m->n, sizeof *m->names, cmp_str);
    size_t u = 0;
    for (size_t k = 0; k < m->n; k++)
        if (!u || strcmp(m->names[u - 1], m->names[k])) m->names[u++] = m->names[k];
    m->n = u;
    m->numeric = u > 0;
    m->ntypes = (long)u;
    long mx = 0, v;
    for (size_t k = 0; k < u && m->numeric; k++) {
        if (!parse_long_tok(m->names[k], &v) || v < 1 || v > 100000000L) m->numeric = 0;
        else if (v > mx) mx = v;
    }
    if (m->numeric) m->ntypes = mx;
}

static long map_number(const type_map *m, const char *name)
{
    long v;
    if (!name) name = "";
    if (m->numeric && parse_long_tok(name, &v)) return v;
    const char **hit = bsearch(&name, m->names, m->n, sizeof *m->names, cmp_str);
    return hit ? (long)(hit - m->names) + 1 : 1;
}

typedef struct data_writer {
    ms_out out;
    int written;
    type_map map[K_KINDS];
} data_writer;

static void *data_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    return ms_out_create(sizeof(data_writer), path, err);
}

/* Bonds (i < j, once) and terms of the view: the count, and each record's type. */
static size_t view_records(const ms_struct_view *v, int kind)
{
    if (kind != K_BOND) return v->count_terms ? v->count_terms(v, kind - K_ANGLE) : 0;
    size_t n = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const unsigned *to;
        size_t nb = v->get_bonds(v, i, &to);
        for (size_t k = 0; k < nb; k++) n += to[k] > i;
    }
    return n;
}

static const char *bond_type(const ms_struct_view *v, size_t i, size_t k)
{
    float order;
    const char *type = "";
    if (v->get_bond_info) v->get_bond_info(v, i, k, &order, &type);
    return type;
}

static int build_maps(data_writer *w, const ms_struct_view *v)
{
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        if (map_add(&w->map[K_ATOM], a.type)) return -1;
        const unsigned *to;
        size_t nb = v->get_bonds(v, i, &to);
        for (size_t k = 0; k < nb; k++)
            if (to[k] > i && map_add(&w->map[K_BOND], bond_type(v, i, k))) return -1;
    }
    for (int kind = K_ANGLE; kind < K_KINDS; kind++) {
        size_t n = view_records(v, kind), at[4];
        for (size_t k = 0; k < n; k++) {
            const char *type;
            v->get_term(v, kind - K_ANGLE, k, at, &type);
            if (map_add(&w->map[kind], type)) return -1;
        }
    }
    for (int kind = 0; kind < K_KINDS; kind++) map_finish(&w->map[kind]);
    return 0;
}

static void write_header(data_writer *w, const ms_struct_view *v, const ms_frame_in *f,
                         const data_style *s, const size_t counts[K_KINDS])
{
    ms_out *o = &w->out;
    ms_out_printf(o, "LAMMPS data file written by molscope (atom_style %s)\n\n", s->name);
    for (int k = 0; k < K_KINDS; k++) ms_out_printf(o, "%zu %s\n", counts[k], count_word[k]);
    ms_out_printf(o, "\n");
    for (int k = 0; k < K_KINDS; k++)
        if (k == K_ATOM || counts[k]) ms_out_printf(o, "%ld %s types\n", w->map[k].ntypes, kind_word[k]);
    ms_lmp_box b;
    ms_lmp_frame_box(v->natoms, f->pos, f->cell, &b);
    static const char *const ax[3] = {"x", "y", "z"};
    ms_out_printf(o, "\n");
    for (int d = 0; d < 3; d++)
        ms_out_printf(o, "%.6f %.6f %slo %shi\n", b.lo[d], b.hi[d], ax[d], ax[d]);
    if (b.triclinic) ms_out_printf(o, "%.6f %.6f %.6f xy xz yz\n", b.xy, b.xz, b.yz);
}

/* Masses: each type's mass, that of its first atom; non-numeric names as comments. */
static void write_masses(data_writer *w, const ms_struct_view *v)
{
    ms_out *o = &w->out;
    const type_map *m = &w->map[K_ATOM];
    ms_out_printf(o, "\nMasses\n\n");
    for (long t = 1; t <= m->ntypes; t++) {
        const char *name = NULL;
        float mass = 0;
        for (size_t i = 0; i < v->natoms; i++) {
            ms_atom_in a;
            v->get_atom(v, i, &a);
            if (map_number(m, a.type) == t) {
                name = a.type ? a.type : "";
                mass = a.mass;
                break;
            }
        }
        if (!name && m->numeric) name = "";
        ms_out_printf(o, "%ld %.4f", t, (double)mass);
        if (!m->numeric && name) ms_out_printf(o, " # %s", name);
        ms_out_printf(o, "\n");
    }
}

static void write_atoms(data_writer *w, const ms_struct_view *v, const ms_frame_in *f,
                        const data_style *s)
{
    ms_out *o = &w->out;
    ms_out_printf(o, "\nAtoms # %s\n\n", s->name);
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        ms_out_printf(o, "%zu", i + 1);
        if (s->mol >= 0) ms_out_printf(o, " %d", a.resid);
        ms_out_printf(o, " %ld", map_number(&w->map[K_ATOM], a.type));
        if (s->q >= 0) ms_out_printf(o, " %.6f", (double)a.charge);
        const float *p = f->pos + 3 * i;
        ms_out_printf(o, " %.6f %.6f %.6f\n", (double)p[0], (double)p[1], (double)p[2]);
    }
    if (!f->vel) return;
    ms_out_printf(o, "\nVelocities\n\n");
    for (size_t i = 0; i < v->natoms; i++)
        ms_out_printf(o, "%zu %.6f %.6f %.6f\n", i + 1, (double)f->vel[3 * i],
                      (double)f->vel[3 * i + 1], (double)f->vel[3 * i + 2]);
}

/* One record: id, type number, atom ids, and the type's name when numbers do not say it. */
static void write_record(data_writer *w, int kind, size_t id, const char *type,
                         const size_t *at)
{
    ms_out *o = &w->out;
    ms_out_printf(o, "%zu %ld", id, map_number(&w->map[kind], type));
    for (int q = 0; q < term_width[kind]; q++) ms_out_printf(o, " %zu", at[q] + 1);
    if (!w->map[kind].numeric && type && *type) ms_out_printf(o, " # %s", type);
    ms_out_printf(o, "\n");
}

static void write_terms(data_writer *w, const ms_struct_view *v, const size_t counts[K_KINDS])
{
    ms_out *o = &w->out;
    if (counts[K_BOND]) {
        ms_out_printf(o, "\nBonds\n\n");
        size_t id = 0;
        for (size_t i = 0; i < v->natoms; i++) {
            const unsigned *to;
            size_t nb = v->get_bonds(v, i, &to);
            for (size_t k = 0; k < nb; k++) {
                size_t at[2] = {i, to[k]};
                if (to[k] > i) write_record(w, K_BOND, ++id, bond_type(v, i, k), at);
            }
        }
    }
    for (int kind = K_ANGLE; kind < K_KINDS; kind++) {
        if (!counts[kind]) continue;
        ms_out_printf(o, "\n%s\n\n", section_of[kind]);
        for (size_t k = 0; k < counts[kind]; k++) {
            size_t at[4];
            const char *type;
            v->get_term(v, kind - K_ANGLE, k, at, &type);
            write_record(w, kind, k + 1, type, at);
        }
    }
}

static int data_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f,
                            ms_perr *err)
{
    data_writer *w = h;
    if (w->written++)
        return ms_perr_set(err, "a LAMMPS data file holds one frame: write one (beg N end N)");
    char want[64] = "full";
    ms_lmp_option(v->options, "atom_style", want, sizeof want);
    const data_style *s = style_named(want);
    if (!s)
        return ms_perr_set(err, "unknown atom style '%.40s': must be atomic, bond, angle, "
                           "molecular, charge or full", want);
    if (build_maps(w, v)) return ms_perr_set(err, "out of memory");
    size_t counts[K_KINDS] = {v->natoms, 0, 0, 0, 0};
    for (int k = K_BOND; k < K_KINDS; k++) counts[k] = view_records(v, k);
    write_header(w, v, f, s, counts);
    write_masses(w, v);
    write_atoms(w, v, f, s);
    write_terms(w, v, counts);
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int data_close_write(void *h, ms_perr *err)
{
    data_writer *w = h;
    for (int k = 0; k < K_KINDS; k++) free(w->map[k].names);
    return ms_out_destroy(w, err);
}

static const ms_plugin data_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "lammpsdata",
    .description = "LAMMPS data file",
    .extensions = "data lammpsdata lmp",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_WRITE_FRAMES,
    .open_read = data_open_read,
    .read_structure = data_read_structure,
    .close_read = data_close_read,
    .open_write = data_open_write,
    .write_frame = data_write_frame,
    .close_write = data_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &data_plugin; }
