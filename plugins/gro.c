/* gro.c: the GROMACS .gro plugin. A frame is a title line (optionally "t= time"), an atom
 * count, fixed-column atom lines (resid 5, resname 5, name 5, number 5, then x y z in the
 * precision the file uses, optionally velocities) and a box line of 3 or 9 numbers (a
 * triclinic box). Lengths are nm in the file and Angstrom here; box vectors become
 * a b c alpha beta gamma. Concatenated frames become frames. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define GRO_PI 3.14159265358979323846

typedef struct gro_reader {
    ms_lines in;
    long natoms;
    long long size;
} gro_reader;

/* One frame's header and box, as read. */
typedef struct gro_frame {
    long n;
    double time;
    int has_time;
    float cell[6];
    size_t width;      /* width of a coordinate field: the distance between decimal points */
} gro_frame;

static void *gro_open_read(const char *path, long *natoms, ms_perr *err)
{
    gro_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    struct stat sb;
    r->size = fstat(fileno(r->in.fp), &sb) == 0 ? (long long)sb.st_size : 0;
    *natoms = -1;
    return r;
}

static void gro_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* "t= 12.5" in a title gives the frame's time (ps). */
static void title_time(const char *l, gro_frame *f)
{
    const char *t = strstr(l, "t=");
    while (t && t > l && t[-1] != ' ') t = strstr(t + 2, "t=");
    if (!t) return;
    t += 2;
    while (*t == ' ') t++;
    size_t n = strcspn(t, " \t");
    if (ms_parse_double(t, n, &f->time) == 1) f->has_time = 1;
}

/* Title and count lines; MS_PLUGIN_EOF when only blank lines remain. */
static int read_head(gro_reader *r, gro_frame *f, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    while ((l = ms_lines_next(in)) && l[strspn(l, " \t")] == '\0') {}
    if (!l) return in->error ? ms_perr_set(err, "read error after line %ld", in->line_no)
                             : MS_PLUGIN_EOF;
    title_time(l, f);
    if (!(l = ms_lines_next(in)))
        return ms_perr_set(err, "line %ld: the file ends before the atom count", in->line_no);
    char *tok[2];
    int nt = ms_tokens(in->line, tok, 2);
    if (nt < 1 || ms_parse_long(tok[0], strlen(tok[0]), &f->n) < 0 || f->n < 1)
        return ms_perr_set(err, "line %ld: bad atom count '%.32s'", in->line_no, nt ? tok[0] : "");
    return MS_PLUGIN_OK;
}

/* Field width from the first atom line: the distance between the first two decimal points
 * after column 20 (8 for GROMACS' default %8.3f). */
static size_t field_width(const char *l, size_t len)
{
    if (len <= 20) return 8;
    const char *d1 = memchr(l + 20, '.', len - 20);
    if (!d1) return 8;
    const char *d2 = memchr(d1 + 1, '.', len - (size_t)(d1 + 1 - l));
    size_t w = d2 ? (size_t)(d2 - d1) : 8;
    return w >= 4 && w <= 30 ? w : 8;
}

/* One atom line: coordinates (and velocities when present) in Angstrom. */
static int read_atom_line(gro_reader *r, gro_frame *f, long k, float pos[3], float vel[3],
                          int *has_vel, ms_perr *err)
{
    ms_lines *in = &r->in;
    if (!ms_lines_next(in)) {
        if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
        return ms_perr_set(err, "line %ld: the file ends after %ld of %ld atoms", in->line_no, k,
                           f->n);
    }
    const char *l = in->line;
    size_t len = in->line_len, w;
    if (k == 0) f->width = field_width(l, len);
    w = f->width;
    if (len < 20 + 3 * w)
        return ms_perr_set(err, "line %ld: atom line too short for coordinates (%zu columns)",
                           in->line_no, len);
    static const char *const axis[3] = {"x", "y", "z"};
    for (size_t d = 0; d < 3; d++) {
        if (ms_field_float(l, len, 20 + d * w, 20 + (d + 1) * w, &pos[d]) != 1) {
            char fld[32];
            ms_field(l, len, 20 + d * w, 20 + (d + 1) * w, fld);
            return ms_perr_set(err, "line %ld: bad %s coordinate '%s'", in->line_no, axis[d], fld);
        }
        pos[d] *= 10.0f;
    }
    *has_vel = len >= 20 + 6 * w;
    for (size_t d = 0; *has_vel && d < 3; d++) {
        if (ms_field_float(l, len, 20 + (3 + d) * w, 20 + (4 + d) * w, &vel[d]) != 1)
            return ms_perr_set(err, "line %ld: bad velocity", in->line_no);
        vel[d] *= 10.0f;
    }
    return MS_PLUGIN_OK;
}

/* Box vectors v1 v2 v3 (nm) -> a b c (Angstrom) and the angles between them (degrees). */
static void box_to_cell(const double v[3][3], float cell[6])
{
    double len[3];
    for (int k = 0; k < 3; k++)
        len[k] = sqrt(v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]);
    static const int pair[3][2] = {{1, 2}, {0, 2}, {0, 1}}; /* alpha, beta, gamma */
    for (int k = 0; k < 3; k++) {
        int i = pair[k][0], j = pair[k][1];
        double c = 90.0;
        if (len[i] > 0 && len[j] > 0) {
            double dot = v[i][0] * v[j][0] + v[i][1] * v[j][1] + v[i][2] * v[j][2];
            double cs = dot / (len[i] * len[j]);
            c = cs == 0.0 ? 90.0 : acos(cs > 1 ? 1 : cs < -1 ? -1 : cs) * 180.0 / GRO_PI;
        }
        cell[k] = (float)(10.0 * len[k]);
        cell[3 + k] = (float)c;
    }
}

/* The box line: v1(x) v2(y) v3(z) [v1(y) v1(z) v2(x) v2(z) v3(x) v3(y)]. */
static int read_box(gro_reader *r, gro_frame *f, ms_perr *err)
{
    ms_lines *in = &r->in;
    if (!ms_lines_next(in)) {
        if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
        return ms_perr_set(err, "line %ld: the file ends before the box line", in->line_no);
    }
    char *tok[9];
    int nt = ms_tokens(in->line, tok, 9);
    double b[9] = {0};
    if (nt != 3 && nt != 9)
        return ms_perr_set(err, "line %ld: box line has %d values, expected 3 or 9", in->line_no,
                           nt);
    for (int k = 0; k < nt; k++)
        if (ms_parse_double(tok[k], strlen(tok[k]), &b[k]) < 0 || fabs(b[k]) > 1e12)
            return ms_perr_set(err, "line %ld: bad box value '%.32s'", in->line_no, tok[k]);
    double v[3][3] = {{b[0], b[3], b[4]}, {b[5], b[1], b[6]}, {b[7], b[8], b[2]}};
    box_to_cell(v, f->cell);
    return MS_PLUGIN_OK;
}

static int gro_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    gro_reader *r = h;
    gro_frame f;
    memset(&f, 0, sizeof f);
    int rc = read_head(r, &f, err);
    if (rc == MS_PLUGIN_EOF) return ms_perr_set(err, "empty file");
    if (rc != MS_PLUGIN_OK) return rc;
    /* an atom line is at least 20 bytes: the file bounds the count */
    if (ms_check_room(err, (double)f.n, 20, ms_lines_left(&r->in), "atoms",
                      "line %ld: the header declares %ld atoms", r->in.line_no, f.n))
        return MS_PLUGIN_ERROR;
    long long most = r->size / 20 + 16;
    sink->reserve(sink, (size_t)(f.n < most ? f.n : most));
    for (long k = 0; k < f.n; k++) {
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        float p[3], v[3];
        int has_vel;
        if (read_atom_line(r, &f, k, p, v, &has_vel, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        const char *l = r->in.line;
        size_t len = r->in.line_len;
        char resname[6], name[6];
        if (ms_field_int(l, len, 0, 5, &a.resid) < 0) {
            char fld[6];
            ms_field(l, len, 0, 5, fld);
            return ms_perr_set(err, "line %ld: bad residue number '%s'", r->in.line_no, fld);
        }
        ms_field(l, len, 5, 10, resname);
        ms_field(l, len, 10, 15, name);
        a.resname = resname;
        a.name = a.type = name;
        a.x = p[0];
        a.y = p[1];
        a.z = p[2];
        a.has = MS_HAS_POS;
        if (has_vel) {
            a.vx = v[0];
            a.vy = v[1];
            a.vz = v[2];
            a.has |= MS_HAS_VEL;
        }
        if (sink->add_atom(sink, &a))
            return ms_perr_set(err, "out of memory at line %ld", r->in.line_no);
    }
    if (read_box(r, &f, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    sink->set_cell(sink, f.cell);
    if (f.has_time) sink->set_time(sink, f.time);
    r->natoms = f.n;
    return MS_PLUGIN_OK;
}

static int gro_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    gro_reader *r = h;
    gro_frame f;
    memset(&f, 0, sizeof f);
    int rc = read_head(r, &f, err);
    if (rc != MS_PLUGIN_OK) return rc;
    if (f.n != natoms)
        return ms_perr_set(err, "line %ld: frame has %ld atoms, expected %ld", r->in.line_no,
                           f.n, natoms);
    for (long k = 0; k < f.n; k++) {
        float p[3], v[3];
        int has_vel;
        if (read_atom_line(r, &f, k, p, v, &has_vel, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        if (fr->pos) memcpy(fr->pos + 3 * k, p, sizeof p);
        if (fr->vel && has_vel) {
            memcpy(fr->vel + 3 * k, v, sizeof v);
            fr->has_vel = 1;
        }
    }
    if (read_box(r, &f, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    memcpy(fr->cell, f.cell, sizeof f.cell);
    fr->has_cell = 1;
    fr->time = f.time;
    fr->has_time = f.has_time;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct gro_writer {
    ms_out out;
} gro_writer;

static void *gro_open_write(const char *path, long natoms, ms_perr *err)
{
    gro_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    return w;
}

/* The cell as GROMACS box vectors (nm): v1 along x, v2 in the xy plane. */
static void write_box(ms_out *o, const float cell[6])
{
    double a = cell[0] / 10.0, b = cell[1] / 10.0, c = cell[2] / 10.0;
    int right = (cell[3] == 90.0f || cell[3] == 0.0f) && (cell[4] == 90.0f || cell[4] == 0.0f) &&
                (cell[5] == 90.0f || cell[5] == 0.0f);
    if (right) {
        ms_out_printf(o, "%10.5f%10.5f%10.5f\n", a, b, c);
        return;
    }
    double ca = cos(cell[3] * GRO_PI / 180.0), cb = cos(cell[4] * GRO_PI / 180.0),
           cg = cos(cell[5] * GRO_PI / 180.0), sg = sin(cell[5] * GRO_PI / 180.0);
    double v2x = b * cg, v2y = b * sg, v3x = c * cb;
    double v3y = sg != 0.0 ? c * (ca - cb * cg) / sg : 0.0;
    double v3z2 = c * c - v3x * v3x - v3y * v3y;
    double v3z = v3z2 > 0 ? sqrt(v3z2) : 0.0;
    ms_out_printf(o, "%10.5f%10.5f%10.5f%10.5f%10.5f%10.5f%10.5f%10.5f%10.5f\n", a, v2y, v3z, 0.0,
                  0.0, v2x, 0.0, v3x, v3y);
}

static int gro_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    gro_writer *w = h;
    ms_out *o = &w->out;
    ms_out_printf(o, "written by molscope, frame %d t= %.5f\n%5zu\n", f->index, f->time,
                  v->natoms);
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        const float *p = f->pos + 3 * i;
        for (int k = 0; k < 3; k++)
            if (!(p[k] > -9999.995f && p[k] < 99999.995f))
                return ms_perr_set(err, "atom %zu: coordinate %g does not fit GRO's 8.3 field",
                                   i + 1, (double)p[k]);
        long resid = ((long)a.resid % 100000 + 100000) % 100000;
        ms_out_printf(o, "%5ld%-5.5s%5.5s%5ld%8.3f%8.3f%8.3f\n", resid, a.resname ? a.resname : "",
                      a.name ? a.name : "", (long)((i + 1) % 100000), p[0] / 10.0, p[1] / 10.0,
                      p[2] / 10.0);
    }
    write_box(o, f->cell);
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int gro_close_write(void *h, ms_perr *err)
{
    gro_writer *w = h;
    return ms_out_destroy(w, err);
}

static const ms_plugin gro_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "gro",
    .description = "GROMACS structure and coordinates",
    .extensions = "gro",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = gro_open_read,
    .read_structure = gro_read_structure,
    .read_frame = gro_read_frame,
    .close_read = gro_close_read,
    .open_write = gro_open_write,
    .write_frame = gro_write_frame,
    .close_write = gro_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &gro_plugin; }
