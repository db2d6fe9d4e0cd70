/* lammpstrj.c: the LAMMPS text dump plugin (VMD's type name `lammpstrj`). Each frame is
 * ITEM: TIMESTEP (and optionally TIME, UNITS), NUMBER OF ATOMS, BOX BOUNDS (orthogonal, or
 * triclinic with "xy xz yz" and the bounding box of the tilted cell) and ATOMS with the
 * columns its header names, in any order. Coordinates are taken, in this order of
 * preference, from xu yu zu (unwrapped), xsu ysu zsu (scaled unwrapped), x y z (wrapped) or
 * xs ys zs (scaled); image flags ix iy iz unwrap the wrapped kinds. Atoms are put in the
 * order of their ids whatever order each frame lists them in; every frame must hold the
 * first one's atoms. The structure comes from the first frame: type (atom name and type;
 * element when given), mol (resid), q, mass, radius or diameter, vx vy vz. The timestep
 * becomes the frame's time. Writes id type x y z frames (boundaries pp, or ss when the frame
 * has no cell). */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "lammps_util.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* The columns molscope reads. */
enum {
    C_ID, C_TYPE, C_ELEMENT, C_MOL, C_Q, C_MASS, C_RADIUS, C_DIAMETER,
    C_X, C_Y, C_Z, C_XS, C_YS, C_ZS, C_XU, C_YU, C_ZU, C_XSU, C_YSU, C_ZSU,
    C_IX, C_IY, C_IZ, C_VX, C_VY, C_VZ, C_N
};
static const char *const col_names[C_N] = {
    "id", "type", "element", "mol", "q", "mass", "radius", "diameter",
    "x", "y", "z", "xs", "ys", "zs", "xu", "yu", "zu", "xsu", "ysu", "zsu",
    "ix", "iy", "iz", "vx", "vy", "vz"};

/* The coordinate kinds, in order of preference: their first column and whether they are
 * scaled and whether image flags apply. */
static const struct {
    int col, scaled, images;
} coord_kinds[4] = {{C_XU, 0, 0}, {C_XSU, 1, 0}, {C_X, 0, 1}, {C_XS, 1, 1}};

#define MAX_COLS 128

typedef struct dump_frame {
    long natoms;
    double timestep, time;
    int has_time;
    ms_lmp_box box;
    int col[C_N];          /* token index of each column, -1 when absent */
    int ncols, coord, images, vel;
    long line;             /* of the ITEM: ATOMS header */
} dump_frame;

typedef struct dump_reader {
    ms_lines in;
    long natoms;
    long *ids;             /* sorted ids of the first frame */
    long *lookup;          /* dense map id - idmin -> index, NULL when ids are sparse */
    long idmin, idspan;
    unsigned *stamp;       /* frame number that last filled each atom */
    unsigned nframe;
    long long *marks;      /* (offset, line number) of each frame told, offsets rising */
    size_t nmarks, capmarks;
} dump_reader;

static void *dump_open_read(const char *path, long *natoms, ms_perr *err)
{
    dump_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void dump_close_read(void *h)
{
    dump_reader *r = h;
    free(r->ids);
    free(r->lookup);
    free(r->stamp);
    free(r->marks);
    ms_lines_destroy(r);
}

/* The next line, or an error naming what the file ended in. */
static const char *need_line(dump_reader *r, const char *what, ms_perr *err)
{
    const char *l = ms_lines_next(&r->in);
    if (!l)
        ms_perr_set(err, r->in.error ? "read error after line %ld"
                                     : "line %ld: the file ends in the %s of a frame",
                    r->in.line_no, what);
    return l;
}

/* The numbers of one line of the header into v (n of them); MS_PLUGIN_OK or an error. */
static int header_numbers(dump_reader *r, const char *what, double *v, int n, ms_perr *err)
{
    const char *l = need_line(r, what, err);
    if (!l) return MS_PLUGIN_ERROR;
    char *tok[8];
    int nt = ms_tokens(r->in.line, tok, 8);
    for (int k = 0; k < n; k++)
        if (k >= nt || ms_parse_double(tok[k], strlen(tok[k]), &v[k]) < 0)
            return ms_perr_set(err, "line %ld: bad %s line", r->in.line_no, what);
    return MS_PLUGIN_OK;
}

static int read_box(dump_reader *r, dump_frame *f, const char *item, ms_perr *err)
{
    f->box.triclinic = strstr(item, "xy") != NULL;
    double tilt[3] = {0, 0, 0};
    for (int d = 0; d < 3; d++) {
        double v[3];
        if (header_numbers(r, "BOX BOUNDS", v, f->box.triclinic ? 3 : 2, err))
            return MS_PLUGIN_ERROR;
        f->box.lo[d] = v[0], f->box.hi[d] = v[1];
        if (f->box.triclinic) tilt[d] = v[2];
    }
    f->box.xy = tilt[0], f->box.xz = tilt[1], f->box.yz = tilt[2];
    if (f->box.triclinic) ms_lmp_box_from_bounds(&f->box);
    return MS_PLUGIN_OK;
}

/* The columns an ITEM: ATOMS line names. */
static int read_columns(dump_reader *r, dump_frame *f, char *names, ms_perr *err)
{
    char *tok[MAX_COLS + 1];
    int nt = ms_tokens(names, tok, MAX_COLS + 1);
    if (nt > MAX_COLS)
        return ms_perr_set(err, "line %ld: more than %d columns", r->in.line_no, MAX_COLS);
    for (int c = 0; c < C_N; c++) f->col[c] = -1;
    for (int k = 0; k < nt; k++)
        for (int c = 0; c < C_N; c++)
            if (!strcmp(tok[k], col_names[c]) && f->col[c] < 0) f->col[c] = k;
    f->ncols = nt;
    f->line = r->in.line_no;
    if (f->col[C_ID] < 0)
        return ms_perr_set(err, "line %ld: the ATOMS columns have no 'id'", r->in.line_no);
    f->coord = -1;
    for (int k = 0; k < 4 && f->coord < 0; k++) {
        int c = coord_kinds[k].col;
        if (f->col[c] >= 0 && f->col[c + 1] >= 0 && f->col[c + 2] >= 0) f->coord = k;
    }
    if (f->coord < 0)
        return ms_perr_set(err, "line %ld: the ATOMS columns have no coordinates (x y z, xs "
                           "ys zs, xu yu zu or xsu ysu zsu)", r->in.line_no);
    f->images = coord_kinds[f->coord].images && f->col[C_IX] >= 0 && f->col[C_IY] >= 0 &&
                f->col[C_IZ] >= 0;
    f->vel = f->col[C_VX] >= 0 && f->col[C_VY] >= 0 && f->col[C_VZ] >= 0;
    return MS_PLUGIN_OK;
}

/* The items of a frame up to and including ITEM: ATOMS; MS_PLUGIN_EOF when only blank
 * lines remain. */
static int read_header(dump_reader *r, dump_frame *f, ms_perr *err)
{
    const char *l;
    int have_n = 0, have_box = 0, first = 1;
    memset(f, 0, sizeof *f);
    for (;;) {
        while ((l = ms_lines_next(&r->in)) && first && l[strspn(l, " \t\r")] == '\0') {}
        if (!l) {
            if (r->in.error) return ms_perr_set(err, "read error after line %ld", r->in.line_no);
            if (first) return MS_PLUGIN_EOF;
            return ms_perr_set(err, "line %ld: the file ends in a frame's header", r->in.line_no);
        }
        if (strncmp(l, "ITEM:", 5))
            return ms_perr_set(err, "line %ld: expected an ITEM: line, found '%.40s'",
                               r->in.line_no, l);
        first = 0;
        const char *item = l + 5 + strspn(l + 5, " \t");
        double v[1];
        if (!strncmp(item, "TIMESTEP", 8)) {
            if (header_numbers(r, "TIMESTEP", v, 1, err)) return MS_PLUGIN_ERROR;
            f->timestep = v[0];
        } else if (!strncmp(item, "TIME", 4)) {
            if (header_numbers(r, "TIME", v, 1, err)) return MS_PLUGIN_ERROR;
            f->time = v[0], f->has_time = 1;
        } else if (!strncmp(item, "UNITS", 5)) {
            if (!need_line(r, "UNITS", err)) return MS_PLUGIN_ERROR;
        } else if (!strncmp(item, "NUMBER OF ATOMS", 15)) {
            if (header_numbers(r, "NUMBER OF ATOMS", v, 1, err)) return MS_PLUGIN_ERROR;
            if (!ms_whole_in(v[0], 1, 2e9))
                return ms_perr_set(err, "line %ld: bad atom count", r->in.line_no);
            f->natoms = (long)v[0], have_n = 1;
        } else if (!strncmp(item, "BOX BOUNDS", 10)) {
            char copy[256];
            snprintf(copy, sizeof copy, "%s", item);
            if (read_box(r, f, copy, err)) return MS_PLUGIN_ERROR;
            have_box = 1;
        } else if (!strncmp(item, "ATOMS", 5)) {
            if (!have_n)
                return ms_perr_set(err, "line %ld: ITEM: ATOMS before NUMBER OF ATOMS",
                                   r->in.line_no);
            (void)have_box;
            return read_columns(r, f, r->in.line + (item - l) + 5, err);
        } else {
            return ms_perr_set(err, "line %ld: unknown item '%.40s'", r->in.line_no, item);
        }
    }
}

/* ---------------------------------------------------------------- atom lines */

/* Split an atom line in place into at most max tokens; the count. */
static int split_atom_line(char *p, char **tok, size_t *len, int max)
{
    int n = 0;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\r') p++;
        if (!*p || n == max) return *p ? max + 1 : n;
        tok[n] = p;
        while (*p && *p != ' ' && *p != '\t' && *p != '\r') p++;
        len[n] = (size_t)(p - tok[n]);
        n++;
    }
}

/* The next atom line of a frame, split; its token count checked. */
static int atom_tokens(dump_reader *r, const dump_frame *f, long k, char **tok, size_t *len,
                       ms_perr *err)
{
    if (!ms_lines_next(&r->in)) {
        if (r->in.error) return ms_perr_set(err, "read error after line %ld", r->in.line_no);
        return ms_perr_set(err, "line %ld: the file ends after %ld of %ld atoms of timestep %.0f",
                           r->in.line_no, k, f->natoms, f->timestep);
    }
    int nt = split_atom_line(r->in.line, tok, len, MAX_COLS);
    if (nt != f->ncols)
        return ms_perr_set(err, "line %ld: %d columns, the ITEM: ATOMS line names %d",
                           r->in.line_no, nt, f->ncols);
    return MS_PLUGIN_OK;
}

static int num_col(dump_reader *r, const dump_frame *f, char **tok, size_t *len, int c,
                   double *v, ms_perr *err)
{
    int k = f->col[c];
    if (ms_parse_double(tok[k], len[k], v) < 0)
        return ms_perr_set(err, "line %ld: bad %s value '%.*s'", r->in.line_no, col_names[c],
                           (int)(len[k] < 32 ? len[k] : 32), tok[k]);
    return MS_PLUGIN_OK;
}

/* An atom line's id and position. */
static int atom_position(dump_reader *r, const dump_frame *f, char **tok, size_t *len,
                         long *id, float xyz[3], ms_perr *err)
{
    double v, s[3], n[3] = {0, 0, 0}, out[3];
    if (num_col(r, f, tok, len, C_ID, &v, err)) return MS_PLUGIN_ERROR;
    if (!ms_whole_in(v, -9e15, 9e15)) return ms_perr_set(err, "line %ld: bad id", r->in.line_no);
    *id = (long)v;
    int c0 = coord_kinds[f->coord].col;
    for (int d = 0; d < 3; d++)
        if (num_col(r, f, tok, len, c0 + d, &s[d], err)) return MS_PLUGIN_ERROR;
    for (int d = 0; f->images && d < 3; d++)
        if (num_col(r, f, tok, len, C_IX + d, &n[d], err)) return MS_PLUGIN_ERROR;
    if (coord_kinds[f->coord].scaled) {
        for (int d = 0; d < 3; d++) s[d] += n[d];
        ms_lmp_to_space(&f->box, s, 1, out);
    } else {
        ms_lmp_to_space(&f->box, n, 0, out);
        for (int d = 0; d < 3; d++) out[d] += s[d];
    }
    for (int d = 0; d < 3; d++) xyz[d] = (float)out[d];
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- ids */

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* Index of an id among the first frame's, -1 when it is not one. */
static long index_of(const dump_reader *r, long id)
{
    if (r->lookup) {
        long k = id - r->idmin;
        return k >= 0 && k <= r->idspan ? r->lookup[k] : -1;
    }
    long *hit = bsearch(&id, r->ids, (size_t)r->natoms, sizeof *r->ids, cmp_long);
    return hit ? (long)(hit - r->ids) : -1;
}

/* Sort the first frame's ids (order[k]: the line of the k-th smallest) and make the map. */
static int index_ids(dump_reader *r, long *ids_in_file, long *order, ms_perr *err)
{
    long n = r->natoms;
    memcpy(r->ids, ids_in_file, (size_t)n * sizeof *r->ids);
    qsort(r->ids, (size_t)n, sizeof *r->ids, cmp_long);
    for (long k = 1; k < n; k++)
        if (r->ids[k] == r->ids[k - 1])
            return ms_perr_set(err, "atom id %ld appears twice in the first frame", r->ids[k]);
    r->idmin = r->ids[0];
    r->idspan = r->ids[n - 1] - r->ids[0];
    if (r->idspan <= 4 * n + 1024 && (r->lookup = malloc(((size_t)r->idspan + 1) * sizeof(long)))) {
        for (long k = 0; k <= r->idspan; k++) r->lookup[k] = -1;
        for (long k = 0; k < n; k++) r->lookup[r->ids[k] - r->idmin] = k;
    }
    for (long k = 0; k < n; k++) order[index_of(r, ids_in_file[k])] = k;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- structure */

/* The per-atom text and numbers of the first frame, kept until they are sorted by id. */
typedef struct first_frame {
    char *text;            /* type '\0' element '\0' per atom, at offsets */
    size_t len, cap;
    size_t *off;
    long *ids, *mol, *order;
    float *pos, *vel, *q, *mass, *radius;
} first_frame;

static void first_free(first_frame *ff)
{
    free(ff->text), free(ff->off), free(ff->ids), free(ff->mol), free(ff->order);
    free(ff->pos), free(ff->vel), free(ff->q), free(ff->mass), free(ff->radius);
}

static int first_alloc(first_frame *ff, long n)
{
    size_t m = (size_t)n;
    ff->off = malloc(m * sizeof *ff->off), ff->ids = malloc(m * sizeof *ff->ids);
    ff->mol = calloc(m, sizeof *ff->mol), ff->order = malloc(m * sizeof *ff->order);
    ff->pos = malloc(3 * m * sizeof *ff->pos), ff->vel = calloc(3 * m, sizeof *ff->vel);
    ff->q = calloc(m, sizeof *ff->q), ff->mass = calloc(m, sizeof *ff->mass);
    ff->radius = calloc(m, sizeof *ff->radius);
    return ff->off && ff->ids && ff->mol && ff->order && ff->pos && ff->vel && ff->q &&
                   ff->mass && ff->radius ? 0 : -1;
}

/* Append the text of a column (or "" when absent) to ff->text. */
static int keep_text(first_frame *ff, const dump_frame *f, char **tok, size_t *len, int c)
{
    size_t n = f->col[c] >= 0 ? len[f->col[c]] : 0;
    if (ff->len + n + 1 > ff->cap) {
        size_t cap = ff->cap ? ff->cap : 4096;
        while (cap < ff->len + n + 1) cap *= 2;
        char *t = realloc(ff->text, cap);
        if (!t) return -1;
        ff->text = t, ff->cap = cap;
    }
    if (n) memcpy(ff->text + ff->len, tok[f->col[c]], n);
    ff->text[ff->len + n] = '\0';
    ff->len += n + 1;
    return 0;
}

/* The optional numeric columns of atom k of the first frame. */
static int first_numbers(dump_reader *r, const dump_frame *f, first_frame *ff, long k,
                         char **tok, size_t *len, ms_perr *err)
{
    double v;
    if (f->col[C_MOL] >= 0) {
        if (num_col(r, f, tok, len, C_MOL, &v, err)) return MS_PLUGIN_ERROR;
        if (!ms_whole_in(v, -2e9, 2e9))
            return ms_perr_set(err, "line %ld: bad molecule id %g", r->in.line_no, v);
        ff->mol[k] = (long)v;
    }
    static const int cols[3] = {C_Q, C_MASS, C_RADIUS};
    float *dst[3] = {ff->q, ff->mass, ff->radius};
    for (int c = 0; c < 3; c++)
        if (f->col[cols[c]] >= 0) {
            if (num_col(r, f, tok, len, cols[c], &v, err)) return MS_PLUGIN_ERROR;
            dst[c][k] = (float)v;
        }
    if (f->col[C_RADIUS] < 0 && f->col[C_DIAMETER] >= 0) {
        if (num_col(r, f, tok, len, C_DIAMETER, &v, err)) return MS_PLUGIN_ERROR;
        ff->radius[k] = (float)(0.5 * v);
    }
    for (int d = 0; f->vel && d < 3; d++) {
        if (num_col(r, f, tok, len, C_VX + d, &v, err)) return MS_PLUGIN_ERROR;
        ff->vel[3 * k + d] = (float)v;
    }
    return MS_PLUGIN_OK;
}

static int read_first_atoms(dump_reader *r, const dump_frame *f, first_frame *ff, ms_perr *err)
{
    char *tok[MAX_COLS];
    size_t len[MAX_COLS];
    for (long k = 0; k < f->natoms; k++) {
        if (atom_tokens(r, f, k, tok, len, err) ||
            atom_position(r, f, tok, len, &ff->ids[k], ff->pos + 3 * k, err) ||
            first_numbers(r, f, ff, k, tok, len, err))
            return MS_PLUGIN_ERROR;
        ff->off[k] = ff->len;
        if (keep_text(ff, f, tok, len, C_TYPE) || keep_text(ff, f, tok, len, C_ELEMENT))
            return ms_perr_set(err, "out of memory");
    }
    return MS_PLUGIN_OK;
}

static int emit_first(dump_reader *r, const dump_frame *f, const first_frame *ff,
                      ms_struct_sink *sink, ms_perr *err)
{
    sink->reserve(sink, (size_t)r->natoms);
    for (long i = 0; i < r->natoms; i++) {
        long k = ff->order[i];
        const char *type = ff->text + ff->off[k], *elem = type + strlen(type) + 1;
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        a.type = type;
        a.name = *elem ? elem : type;
        a.element = *elem ? elem : NULL;
        a.resid = (int)ff->mol[k];
        a.charge = ff->q[k], a.mass = ff->mass[k], a.radius = ff->radius[k];
        a.has = MS_HAS_POS | (f->col[C_Q] >= 0 ? MS_HAS_CHARGE : 0) |
                (f->col[C_MASS] >= 0 ? MS_HAS_MASS : 0) |
                (f->col[C_RADIUS] >= 0 || f->col[C_DIAMETER] >= 0 ? MS_HAS_RADIUS : 0) |
                (f->vel ? MS_HAS_VEL : 0);
        a.x = ff->pos[3 * k], a.y = ff->pos[3 * k + 1], a.z = ff->pos[3 * k + 2];
        a.vx = ff->vel[3 * k], a.vy = ff->vel[3 * k + 1], a.vz = ff->vel[3 * k + 2];
        if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory");
    }
    float cell[6];
    if (ms_lmp_box_to_cell(&f->box, cell)) sink->set_cell(sink, cell);
    sink->set_time(sink, f->has_time ? f->time : f->timestep);
    return MS_PLUGIN_OK;
}

static int dump_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    dump_reader *r = h;
    dump_frame f;
    int rc = read_header(r, &f, err);
    if (rc == MS_PLUGIN_EOF) return ms_perr_set(err, "empty file");
    if (rc) return rc;
    /* an atom line holds at least an id and three coordinates */
    if (ms_check_room(err, (double)f.natoms, 8, ms_lines_left(&r->in), "atoms",
                      "line %ld: NUMBER OF ATOMS says %ld", f.line, f.natoms))
        return MS_PLUGIN_ERROR;
    r->natoms = f.natoms;
    first_frame ff;
    memset(&ff, 0, sizeof ff);
    if (first_alloc(&ff, f.natoms) || !(r->ids = malloc((size_t)f.natoms * sizeof *r->ids)) ||
        !(r->stamp = calloc((size_t)f.natoms, sizeof *r->stamp)))
        rc = ms_perr_set(err, "out of memory for %ld atoms", f.natoms);
    if (!rc) rc = read_first_atoms(r, &f, &ff, err);
    if (!rc) rc = index_ids(r, ff.ids, ff.order, err);
    if (!rc) rc = emit_first(r, &f, &ff, sink, err);
    first_free(&ff);
    return rc;
}

/* ---------------------------------------------------------------- frames */

static int dump_read_frame(void *h, long natoms, ms_frame_out *out, ms_perr *err)
{
    dump_reader *r = h;
    dump_frame f;
    int rc = read_header(r, &f, err);
    if (rc) return rc;
    if (f.natoms != natoms)
        return ms_perr_set(err, "line %ld: timestep %.0f has %ld atoms, the first frame had %ld "
                           "(LAMMPS dumps with a changing atom count cannot be read)",
                           f.line, f.timestep, f.natoms, natoms);
    unsigned stamp = ++r->nframe;
    char *tok[MAX_COLS];
    size_t len[MAX_COLS];
    for (long k = 0; k < f.natoms; k++) {
        long id, i;
        float p[3];
        if (atom_tokens(r, &f, k, tok, len, err) || atom_position(r, &f, tok, len, &id, p, err))
            return MS_PLUGIN_ERROR;
        if ((i = index_of(r, id)) < 0 || r->stamp[i] == stamp)
            return ms_perr_set(err, "line %ld: atom id %ld %s", r->in.line_no, id,
                               i < 0 ? "is not in the first frame" : "appears twice");
        r->stamp[i] = stamp;
        if (out->pos) memcpy(out->pos + 3 * i, p, sizeof p);
        for (int d = 0; out->vel && f.vel && d < 3; d++) {
            double v;
            if (num_col(r, &f, tok, len, C_VX + d, &v, err)) return MS_PLUGIN_ERROR;
            out->vel[3 * i + d] = (float)v;
        }
    }
    out->has_vel = out->vel && f.vel;
    out->has_cell = ms_lmp_box_to_cell(&f.box, out->cell);
    out->time = f.has_time ? f.time : f.timestep;
    out->has_time = 1;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- seeking */

/* Frames are found by the byte offset of the line after the last one read (the frame's
 * ITEM: TIMESTEP line, or blank lines before it). Each offset told is remembered with its
 * line number, so that messages after a seek still name the file's true lines. */
static int dump_tell_frame(void *h, long long *token, ms_perr *err)
{
    dump_reader *r = h;
    long long at = ms_lines_tell_next(&r->in);
    if (!r->nmarks || at > r->marks[2 * (r->nmarks - 1)]) {
        if (r->nmarks == r->capmarks) {
            size_t cap = r->capmarks ? 2 * r->capmarks : 64;
            long long *m = realloc(r->marks, cap * 2 * sizeof *m);
            if (!m) return ms_perr_set(err, "out of memory for the frame offsets");
            r->marks = m, r->capmarks = cap;
        }
        r->marks[2 * r->nmarks] = at;
        r->marks[2 * r->nmarks++ + 1] = r->in.line_no;
    }
    *token = at;
    return MS_PLUGIN_OK;
}

/* The line number before offset at, as told; 0 when it was never told. */
static long line_before(const dump_reader *r, long long at)
{
    size_t lo = 0, hi = r->nmarks;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (r->marks[2 * mid] < at) lo = mid + 1;
        else hi = mid;
    }
    return lo < r->nmarks && r->marks[2 * lo] == at ? (long)r->marks[2 * lo + 1] : 0;
}

static int dump_seek_frame(void *h, long long token, ms_perr *err)
{
    dump_reader *r = h;
    if (token < 0 || ms_lines_seek(&r->in, token, line_before(r, token)) != 0)
        return ms_perr_set(err, "cannot seek to byte %lld: %s", token, strerror(errno));
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct dump_writer {
    ms_out out;
} dump_writer;

static void *dump_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    return ms_out_create(sizeof(dump_writer), path, err);
}

static int dump_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f,
                            ms_perr *err)
{
    dump_writer *w = h;
    ms_out *o = &w->out;
    ms_lmp_box b;
    /* no cell: LAMMPS' shrink-wrapped boundaries, as VMD writes them */
    const char *bc = ms_lmp_frame_box(v->natoms, f->pos, f->cell, &b) ? "pp pp pp" : "ss ss ss";
    double lo[3], hi[3];
    ms_lmp_bounds_of_box(&b, lo, hi);
    ms_out_printf(o, "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%zu\n", f->index, v->natoms);
    ms_out_printf(o, "ITEM: BOX BOUNDS %s%s\n", b.triclinic ? "xy xz yz " : "", bc);
    double tilt[3] = {b.xy, b.xz, b.yz};
    for (int d = 0; d < 3; d++) {
        ms_out_printf(o, "%.6f %.6f", lo[d], hi[d]);
        if (b.triclinic) ms_out_printf(o, " %.6f", tilt[d]);
        ms_out_printf(o, "\n");
    }
    ms_out_printf(o, "ITEM: ATOMS id type x y z\n");
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        const float *p = f->pos + 3 * i;
        ms_out_printf(o, "%zu %s %.5f %.5f %.5f\n", i + 1, a.type && *a.type ? a.type : "1",
                      (double)p[0], (double)p[1], (double)p[2]);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int dump_close_write(void *h, ms_perr *err)
{
    return ms_out_destroy(h, err);
}

static const ms_plugin dump_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "lammpstrj",
    .description = "LAMMPS text dump (trajectory)",
    .extensions = "lammpstrj lammpsdump",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = dump_open_read,
    .read_structure = dump_read_structure,
    .read_frame = dump_read_frame,
    .close_read = dump_close_read,
    .tell_frame = dump_tell_frame,
    .seek_frame = dump_seek_frame,
    .open_write = dump_open_write,
    .write_frame = dump_write_frame,
    .close_write = dump_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &dump_plugin; }
