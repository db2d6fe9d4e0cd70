/* crd.c: AMBER's ASCII trajectory (mdcrd), VMD's type `crd` (.mdcrd .crd), and built a
 * second time as `crdbox` by crdbox.c (the same frames, each followed by a box line). A
 * title line, then per frame the 3N coordinates in 8 columns, ten a line, a frame starting
 * on a new line. The file does not say N: the structure loaded before gives it, and a frame
 * whose lines do not fall where N atoms put them, or a file that is not a whole number of
 * such frames, is refused as a wrong atom count. Reads and writes frames. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <string.h>

#ifndef CRD_WITH_BOX
#define CRD_WITH_BOX 0
#define CRD_TYPE_NAME "crd"
#define CRD_DESCRIPTION "AMBER ASCII trajectory (mdcrd), no box"
#define CRD_EXTENSIONS "mdcrd crd"
#endif

#define CRD_W 8        /* columns of a value */
#define CRD_PER_LINE 10

typedef struct crd_reader {
    ms_lines in;
    long long data_start;  /* offset of the first frame */
    long long size;        /* file size, -1 when unknown */
    long frames;
} crd_reader;

static void *crd_open_read(const char *path, long *natoms, ms_perr *err)
{
    crd_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    if (!ms_lines_next(&r->in)) {
        ms_lines_destroy(r);
        ms_perr_set(err, "the file is empty (a crd file starts with a title line)");
        return NULL;
    }
    r->data_start = ms_lines_tell_next(&r->in);
    long long left = ms_lines_left(&r->in);
    r->size = left < 0 ? -1 : r->data_start + left;
    *natoms = -1; /* the structure says */
    return r;
}

static void crd_close_read(void *h) { ms_lines_destroy(h); }

/* Values on the current line: its length in fields of 8 columns (trailing blanks and a
 * carriage return dropped). */
static size_t line_fields(const ms_lines *in)
{
    size_t len = in->line_len;
    while (len && (in->line[len - 1] == ' ' || in->line[len - 1] == '\r')) len--;
    return (len + CRD_W - 1) / CRD_W;
}

static int parse_line(ms_lines *in, size_t n, float *dst, ms_perr *err)
{
    for (size_t f = 0; f < n; f++) {
        int rc = ms_field_float(in->line, in->line_len, f * CRD_W, (f + 1) * CRD_W, &dst[f]);
        if (rc != 1)
            return ms_perr_set(err, "line %ld: bad number in columns %zu-%zu", in->line_no,
                               f * CRD_W + 1, (f + 1) * CRD_W);
    }
    return MS_PLUGIN_OK;
}

static int wrong_count(ms_lines *in, size_t got, size_t want, long natoms, ms_perr *err)
{
    return ms_perr_set(err, "line %ld: %zu values where a frame of %ld atoms (the structure's "
                            "count) has %zu: wrong atom count%s", in->line_no, got, natoms, want,
                       CRD_WITH_BOX ? " (or a file without box: type crd)"
                                    : " (or a file with a box: type crdbox)");
}

/* The 3N coordinates of one frame (into pos, or a scratch line when skipping). Returns
 * MS_PLUGIN_EOF at the end of the file before the frame starts. */
static int read_coords(crd_reader *r, long natoms, float *pos, ms_perr *err)
{
    size_t total = 3 * (size_t)natoms, done = 0;
    float scratch[CRD_PER_LINE];
    while (done < total) {
        if (!ms_lines_next(&r->in)) {
            if (r->in.error) return ms_perr_set(err, "read error after line %ld", r->in.line_no);
            if (done == 0) return MS_PLUGIN_EOF;
            return ms_perr_set(err, "truncated: the file ends after %zu of the frame's %zu "
                                    "values (%ld atoms)", done, total, natoms);
        }
        size_t want = total - done < CRD_PER_LINE ? total - done : CRD_PER_LINE;
        size_t got = line_fields(&r->in);
        if (got != want) return wrong_count(&r->in, got, want, natoms, err);
        if (parse_line(&r->in, got, pos ? pos + done : scratch, err)) return MS_PLUGIN_ERROR;
        done += got;
    }
    return MS_PLUGIN_OK;
}

/* The box line of crdbox: the three lengths (three more values, the angles, are allowed). */
static int read_box(crd_reader *r, long natoms, ms_frame_out *fr, ms_perr *err)
{
    if (!ms_lines_next(&r->in))
        return ms_perr_set(err, "truncated: the file ends before the box line of frame %ld",
                           r->frames);
    size_t got = line_fields(&r->in);
    if (got != 3 && got != 6) return wrong_count(&r->in, got, 3, natoms, err);
    float v[6] = {0, 0, 0, 90, 90, 90};
    if (parse_line(&r->in, got, v, err)) return MS_PLUGIN_ERROR;
    memcpy(fr->cell, v, sizeof fr->cell);
    fr->has_cell = 1;
    return MS_PLUGIN_OK;
}

/* After the first frame: the rest of the file must be a whole number of frames of its size
 * (each frame takes as many bytes as the first in the fixed layout writers use). */
static int check_frame_size(crd_reader *r, long natoms, ms_perr *err)
{
    long long frame = ms_lines_tell_next(&r->in) - r->data_start;
    long long data = r->size - r->data_start;
    if (r->size < 0 || frame <= 0 || data % frame == 0) return MS_PLUGIN_OK;
    /* A last line without its newline is one byte short. */
    if ((data + 1) % frame == 0) return MS_PLUGIN_OK;
    return ms_perr_set(err, "truncated file or wrong atom count: the %lld bytes of frames are "
                            "not a whole number of %ld-atom frames (%lld bytes each)%s", data,
                       natoms, frame,
                       CRD_WITH_BOX ? "" : " (a file with a box is type crdbox)");
}

static int crd_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    crd_reader *r = h;
    if (natoms <= 0)
        return ms_perr_set(err, "a crd file does not give the atom count: load a structure "
                                "(prmtop, psf, pdb) first");
    int rc = read_coords(r, natoms, fr->pos, err);
    if (rc != MS_PLUGIN_OK) return rc;
    if (CRD_WITH_BOX && read_box(r, natoms, fr, err)) return MS_PLUGIN_ERROR;
    if (r->frames++ == 0 && check_frame_size(r, natoms, err)) return MS_PLUGIN_ERROR;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct crd_writer {
    ms_out out;
    long natoms;
} crd_writer;

static void *crd_open_write(const char *path, long natoms, ms_perr *err)
{
    crd_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    w->natoms = natoms;
    ms_out_printf(&w->out, "%-80s\n", "written by molscope");
    return w;
}

/* Values v[0..n) as one line of 8-column fields; -1 when one does not fit. */
static int put_line(ms_out *o, const float *v, size_t n)
{
    char buf[CRD_PER_LINE * CRD_W + 2];
    size_t at = 0;
    for (size_t k = 0; k < n; k++) {
        double x = v[k];
        if (!(x > -999.9995 && x < 9999.9995)) return -1;
        at += (size_t)snprintf(buf + at, sizeof buf - at, "%8.3f", x);
    }
    buf[at++] = '\n';
    ms_out_write(o, buf, at);
    return 0;
}

static int crd_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    crd_writer *w = h;
    size_t total = 3 * v->natoms;
    for (size_t done = 0; done < total; done += CRD_PER_LINE) {
        size_t n = total - done < CRD_PER_LINE ? total - done : CRD_PER_LINE;
        if (put_line(&w->out, f->pos + done, n))
            return ms_perr_set(err, "frame %d: atom %zu: a coordinate does not fit the crd "
                                    "format's 8 columns (-999.999 to 9999.999)",
                               f->index, done / 3 + 1);
    }
    if (CRD_WITH_BOX && put_line(&w->out, f->cell, 3))
        return ms_perr_set(err, "frame %d: the box does not fit 8 columns", f->index);
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int crd_close_write(void *h, ms_perr *err) { return ms_out_destroy(h, err); }

static const ms_plugin crd_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = CRD_TYPE_NAME,
    .description = CRD_DESCRIPTION,
    .extensions = CRD_EXTENSIONS,
    .caps = MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = crd_open_read,
    .read_frame = crd_read_frame,
    .close_read = crd_close_read,
    .open_write = crd_open_write,
    .write_frame = crd_write_frame,
    .close_write = crd_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &crd_plugin; }
