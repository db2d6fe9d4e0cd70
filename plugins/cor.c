/* cor.c: the CHARMM coordinate plugin (.cor, or .crd with type cor: VMD's type name; .crd
 * alone is AMBER's). Title lines starting with '*', an atom count ("N" or, for the extended
 * format, "N  EXT"), then one fixed-column line per atom:
 *   standard (I5,I5,1X,A4,1X,A4,3F10.5,1X,A4,1X,A4,F10.5)
 *   EXT      (I10,I10,2X,A8,2X,A8,3F20.10,2X,A8,2X,A8,F20.10)
 * atom number, residue number (sequential), resname, atom name, x y z, segid, resid (the
 * residue's own identifier, with an insertion letter if any), weight. resid is read from
 * the resid column (the residue number when it is blank), the weight as beta. One frame.
 * Writes the standard format, or EXT when there are more than 99999 atoms or a name,
 * resname or segname is longer than 4 characters. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Columns of one format: [start, end) of each field. */
typedef struct cor_cols {
    int resno[2], resname[2], name[2], xyz[3][2], segid[2], resid[2], weight[2];
} cor_cols;

static const cor_cols cor_std = {{5, 10}, {11, 15}, {16, 20}, {{20, 30}, {30, 40}, {40, 50}},
                                 {51, 55}, {56, 60}, {60, 70}};
static const cor_cols cor_ext = {{10, 20}, {22, 30}, {32, 40},
                                 {{40, 60}, {60, 80}, {80, 100}}, {102, 110}, {112, 120},
                                 {120, 140}};

typedef struct cor_reader {
    ms_lines in;
} cor_reader;

static void *cor_open_read(const char *path, long *natoms, ms_perr *err)
{
    cor_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    *natoms = -1;
    return r;
}

static void cor_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* Title lines (kept as remarks), then the count line: *n atoms, *ext the format. */
static int read_header(cor_reader *r, ms_struct_sink *sink, long *n, int *ext, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    while ((l = ms_lines_next(in)) && l[0] == '*') {
        const char *t = l + 1 + (l[1] == ' ');
        if (*t && sink->add_remark(sink, t)) return ms_perr_set(err, "out of memory");
    }
    if (!l) return in->error ? ms_perr_set(err, "read error after line %ld", in->line_no)
                             : ms_perr_set(err, "line %ld: the file ends before the atom count",
                                           in->line_no);
    char *tok[3];
    int nt = ms_tokens(in->line, tok, 3);
    if (nt < 1 || nt > 2 || ms_parse_long(tok[0], strlen(tok[0]), n) < 0 || *n < 1 ||
        *n > 0x7fffffffL || (nt == 2 && strcmp(tok[1], "EXT") != 0))
        return ms_perr_set(err, "line %ld: expected the atom count ('N' or 'N  EXT'), found "
                           "'%.40s'", in->line_no, nt ? tok[0] : "");
    *ext = nt == 2;
    return MS_PLUGIN_OK;
}

/* resid "12" or "12A": the number and the insertion letter; 0 when it is not one. */
static int parse_resid(const char *s, int *resid, char *ins)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || v < -99999999L || v > 999999999L) return 0;
    if (*end && (!isalpha((unsigned char)*end) || end[1])) return 0;
    *resid = (int)v;
    *ins = *end ? *end : ' ';
    return 1;
}

/* One atom line into a (strings in the caller's buffers). */
static int read_atom(cor_reader *r, const cor_cols *c, long k, long n, ms_atom_in *a,
                     char buf[4][16], ms_perr *err)
{
    ms_lines *in = &r->in;
    if (!ms_lines_next(in)) {
        if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
        return ms_perr_set(err, "line %ld: the file ends after %ld of %ld atoms", in->line_no, k,
                           n);
    }
    const char *l = in->line;
    size_t len = in->line_len;
    memset(a, 0, sizeof *a);
    float xyz[3];
    static const char *const axis[3] = {"x", "y", "z"};
    for (int d = 0; d < 3; d++)
        if (ms_field_float(l, len, c->xyz[d][0], c->xyz[d][1], &xyz[d]) != 1) {
            char f[24];
            ms_field(l, len, c->xyz[d][0], c->xyz[d][1], f);
            return ms_perr_set(err, "line %ld: bad %s coordinate '%s'", in->line_no, axis[d], f);
        }
    ms_field(l, len, c->resname[0], c->resname[1], buf[0]);
    ms_field(l, len, c->name[0], c->name[1], buf[1]);
    ms_field(l, len, c->segid[0], c->segid[1], buf[2]);
    ms_field(l, len, c->resid[0], c->resid[1], buf[3]);
    if (!parse_resid(buf[3], &a->resid, &a->insertion) &&
        ms_field_int(l, len, c->resno[0], c->resno[1], &a->resid) != 1)
        return ms_perr_set(err, "line %ld: bad residue identifier '%s'", in->line_no, buf[3]);
    if (ms_field_float(l, len, c->weight[0], c->weight[1], &a->beta) == 1) a->has |= MS_HAS_BETA;
    a->resname = buf[0];
    a->name = a->type = buf[1];
    a->segname = buf[2];
    a->x = xyz[0];
    a->y = xyz[1];
    a->z = xyz[2];
    a->has |= MS_HAS_POS;
    return MS_PLUGIN_OK;
}

static int cor_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    cor_reader *r = h;
    long n;
    int ext;
    if (read_header(r, sink, &n, &ext, err)) return MS_PLUGIN_ERROR;
    const cor_cols *c = ext ? &cor_ext : &cor_std;
    /* an atom line holds at least its coordinates */
    if (ms_check_room(err, (double)n, c->xyz[2][1], ms_lines_left(&r->in), "atoms",
                      "line %ld: the header declares %ld atoms", r->in.line_no, n))
        return MS_PLUGIN_ERROR;
    sink->reserve(sink, (size_t)n);
    for (long k = 0; k < n; k++) {
        ms_atom_in a;
        char buf[4][16];
        if (read_atom(r, c, k, n, &a, buf, err)) return MS_PLUGIN_ERROR;
        if (sink->add_atom(sink, &a))
            return ms_perr_set(err, "out of memory at line %ld", r->in.line_no);
    }
    return MS_PLUGIN_OK;
}

static int cor_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    (void)h, (void)natoms, (void)fr, (void)err;
    return MS_PLUGIN_EOF; /* one frame, given with the structure */
}

/* ---------------------------------------------------------------- writing */

typedef struct cor_writer {
    ms_out out;
    int frames;
} cor_writer;

static void *cor_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    return ms_out_create(sizeof(cor_writer), path, err);
}

static const char *or_blank(const char *s) { return s ? s : ""; }

/* The extended format is needed for this view. */
static int needs_ext(const ms_struct_view *v)
{
    if (v->natoms > 99999) return 1;
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        if (strlen(or_blank(a.name)) > 4 || strlen(or_blank(a.resname)) > 4 ||
            strlen(or_blank(a.segname)) > 4 || a.resid > 9999 || a.resid < -999)
            return 1;
    }
    return 0;
}

/* Residue numbers count residues from 1: a new one where resid, insertion, resname or
 * segname change. */
static int new_residue(const ms_atom_in *a, const ms_atom_in *prev)
{
    return a->resid != prev->resid || a->insertion != prev->insertion ||
           strcmp(or_blank(a->resname), or_blank(prev->resname)) != 0 ||
           strcmp(or_blank(a->segname), or_blank(prev->segname)) != 0;
}

static int cor_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    cor_writer *w = h;
    ms_out *o = &w->out;
    if (w->frames++) return ms_perr_set(err, "a CHARMM coordinate file holds one frame: write one");
    int ext = needs_ext(v);
    double lim = ext ? 1e9 : 9999.99999;
    ms_out_printf(o, "* written by molscope\n*\n");
    ms_out_printf(o, ext ? "%10zu  EXT\n" : "%5zu\n", v->natoms);
    ms_atom_in a, prev;
    long resno = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        v->get_atom(v, i, &a);
        if (i == 0 || new_residue(&a, &prev)) resno++;
        prev = a;
        const float *p = f->pos + 3 * i;
        for (int d = 0; d < 3; d++)
            if (!(fabs(p[d]) < lim))
                return ms_perr_set(err, "atom %zu: coordinate %g does not fit the format",
                                   i + 1, (double)p[d]);
        char resid[16];
        snprintf(resid, sizeof resid, "%d%c", a.resid,
                 a.insertion && a.insertion != ' ' ? a.insertion : '\0');
        if (ext)
            ms_out_printf(o, "%10zu%10ld  %-8.8s  %-8.8s%20.10f%20.10f%20.10f  %-8.8s  %-8.8s"
                          "%20.10f\n", i + 1, resno, or_blank(a.resname), or_blank(a.name),
                          (double)p[0], (double)p[1], (double)p[2], or_blank(a.segname), resid,
                          (double)a.beta);
        else
            ms_out_printf(o, "%5zu%5ld %-4.4s %-4.4s%10.5f%10.5f%10.5f %-4.4s %-4.4s%10.5f\n",
                          i + 1, resno % 100000, or_blank(a.resname), or_blank(a.name),
                          (double)p[0], (double)p[1], (double)p[2], or_blank(a.segname), resid,
                          (double)a.beta);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int cor_close_write(void *h, ms_perr *err)
{
    return ms_out_destroy(h, err);
}

static const ms_plugin cor_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "cor",
    .description = "CHARMM coordinates (standard and EXT)",
    .extensions = "cor",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = cor_open_read,
    .read_structure = cor_read_structure,
    .read_frame = cor_read_frame,
    .close_read = cor_close_read,
    .open_write = cor_open_write,
    .write_frame = cor_write_frame,
    .close_write = cor_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &cor_plugin; }
