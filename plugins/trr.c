/* trr.c: the GROMACS TRR trajectory plugin: full-precision frames in XDR (big-endian). A
 * frame is a header (magic 1993, the version string "GMX_trn_file", the byte sizes of the
 * blocks that follow, atom count, step, then time and lambda in the file's precision) and
 * the blocks present: box, virial, pressure, positions, velocities, forces, each in single
 * or double precision (told by the block sizes). Lengths are nm in the file and Angstrom
 * here; velocities nm/ps -> A/ps. Frames that hold no positions (velocities or forces only)
 * are skipped. Writes single-precision frames with box and positions. */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "gmx_util.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TRR_MAGIC 1993

typedef struct trr_reader {
    FILE *fp;
    long natoms;
    long long size;
    unsigned char *buf;
    size_t buf_cap;
} trr_reader;

enum { S_IR, S_E, S_BOX, S_VIR, S_PRES, S_TOP, S_SYM, S_X, S_V, S_F, S_NATOMS, S_STEP, S_NRE,
       S_COUNT };

typedef struct trr_head {
    int32_t s[S_COUNT];
    int dbl;
    double time;
} trr_head;

static double be_real(const unsigned char *p, int dbl)
{
    if (!dbl) return ms_be_float(p);
    uint64_t v = (uint64_t)ms_be32(p) << 32 | ms_be32(p + 4);
    double d;
    memcpy(&d, &v, 8);
    return d;
}

static int read_exact(FILE *fp, void *b, size_t n)
{
    size_t got = fread(b, 1, n, fp);
    if (got == n) return 1;
    return got == 0 && feof(fp) ? 0 : -1;
}

/* One frame header. MS_PLUGIN_EOF at a clean end of file. */
static int read_head(trr_reader *r, trr_head *h, ms_perr *err)
{
    unsigned char b[8];
    int got = read_exact(r->fp, b, 8);
    if (got == 0) return MS_PLUGIN_EOF;
    if (got < 0) return ms_perr_set(err, "truncated: the file ends in a frame header");
    if ((int32_t)ms_be32(b) != TRR_MAGIC)
        return ms_perr_set(err, "bad magic number %d, expected 1993", (int)(int32_t)ms_be32(b));
    unsigned char l[4];
    if (read_exact(r->fp, l, 4) != 1) return ms_perr_set(err, "truncated: in the version string");
    uint32_t len = ms_be32(l);
    if (len > 128) return ms_perr_set(err, "bad version string length %u", len);
    unsigned char skip[132], ints[S_COUNT * 4];
    if (read_exact(r->fp, skip, (len + 3) & ~3u) != 1 ||
        read_exact(r->fp, ints, sizeof ints) != 1)
        return ms_perr_set(err, "truncated: the file ends in a frame header");
    for (int k = 0; k < S_COUNT; k++) {
        h->s[k] = (int32_t)ms_be32(ints + 4 * k);
        if (h->s[k] < 0 && k != S_STEP) return ms_perr_set(err, "bad header field %d", k);
    }
    int32_t n = h->s[S_NATOMS];
    if (n < 1) return ms_perr_set(err, "bad atom count %d", (int)n);
    if (h->s[S_BOX]) h->dbl = h->s[S_BOX] == 9 * 8;
    else if (h->s[S_X]) h->dbl = (long long)h->s[S_X] == 3LL * 8 * n;
    else if (h->s[S_V]) h->dbl = (long long)h->s[S_V] == 3LL * 8 * n;
    else h->dbl = (long long)h->s[S_F] == 3LL * 8 * n;
    int rs = h->dbl ? 8 : 4;
    if ((h->s[S_BOX] && h->s[S_BOX] != 9 * rs) || (h->s[S_VIR] && h->s[S_VIR] != 9 * rs) ||
        (h->s[S_PRES] && h->s[S_PRES] != 9 * rs))
        return ms_perr_set(err, "bad box, virial or pressure block size");
    for (int k = S_X; k <= S_F; k++)
        if (h->s[k] && (long long)h->s[k] != 3LL * rs * n)
            return ms_perr_set(err, "bad %s block size %d for %d atoms",
                               k == S_X ? "position" : k == S_V ? "velocity" : "force",
                               (int)h->s[k], (int)n);
    if (h->s[S_IR] || h->s[S_E] || h->s[S_TOP] || h->s[S_SYM])
        return ms_perr_set(err, "unsupported blocks (input record, energies or topology)");
    unsigned char t[16];
    if (read_exact(r->fp, t, 2 * (size_t)rs) != 1)
        return ms_perr_set(err, "truncated: the file ends in a frame header");
    h->time = be_real(t, h->dbl);
    return MS_PLUGIN_OK;
}

static void trr_close_read(void *h)
{
    trr_reader *r = h;
    if (r->fp) fclose(r->fp);
    free(r->buf);
    free(r);
}

static void *trr_open_read(const char *path, long *natoms, ms_perr *err)
{
    trr_reader *r = calloc(1, sizeof *r);
    trr_head h;
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (!(r->fp = ms_open_sized(path, &r->size, err))) goto fail;
    int rc = read_head(r, &h, err);
    if (rc == MS_PLUGIN_EOF) ms_perr_set(err, "not a TRR file: empty");
    if (rc != MS_PLUGIN_OK) goto fail;
    /* A frame with positions (the only kind kept) takes at least 12 bytes per atom. */
    if ((double)h.s[S_NATOMS] * 12.0 > (double)r->size) {
        ms_perr_set(err, "frame 0: the header declares %d atoms, but their positions (12 bytes "
                    "each or more) do not fit in the file's %lld bytes", (int)h.s[S_NATOMS],
                    r->size);
        goto fail;
    }
    rewind(r->fp);
    r->natoms = *natoms = h.s[S_NATOMS];
    return r;
fail:
    trr_close_read(r);
    return NULL;
}

/* Read a block of n reals into out (scaled), or skip it when out is NULL. */
static int read_block(trr_reader *r, size_t bytes, int dbl, float *out, float scale,
                      ms_perr *err)
{
    if (!bytes) return MS_PLUGIN_OK;
    if ((long long)bytes > r->size)
        return ms_perr_set(err, "truncated: a data block of %zu bytes in a %lld-byte file", bytes,
                           r->size);
    if (!out) return fseeko(r->fp, (off_t)bytes, SEEK_CUR) == 0 ? MS_PLUGIN_OK
                                                                : ms_perr_set(err, "seek failed");
    if (bytes > r->buf_cap) {
        unsigned char *nb = realloc(r->buf, bytes);
        if (!nb) return ms_perr_set(err, "out of memory");
        r->buf = nb;
        r->buf_cap = bytes;
    }
    if (read_exact(r->fp, r->buf, bytes) != 1)
        return ms_perr_set(err, "truncated: the file ends in a data block");
    size_t n = bytes / (dbl ? 8 : 4);
    for (size_t k = 0; k < n; k++) out[k] = (float)(be_real(r->buf + k * (dbl ? 8 : 4), dbl) * scale);
    return MS_PLUGIN_OK;
}

static int trr_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    trr_reader *r = h;
    for (;;) {
        trr_head hd;
        int rc = read_head(r, &hd, err);
        if (rc != MS_PLUGIN_OK) return rc;
        if (hd.s[S_NATOMS] != natoms)
            return ms_perr_set(err, "the frame has %d atoms, expected %ld", (int)hd.s[S_NATOMS],
                               natoms);
        int rs = hd.dbl ? 8 : 4;
        if (hd.s[S_BOX]) {
            unsigned char b[72];
            if (read_exact(r->fp, b, 9 * (size_t)rs) != 1)
                return ms_perr_set(err, "truncated: the file ends in the box");
            double box[9];
            for (int k = 0; k < 9; k++) box[k] = be_real(b + k * rs, hd.dbl);
            ms_gmx_box_to_cell(box, fr->cell);
            fr->has_cell = 1;
        }
        if (read_block(r, (size_t)hd.s[S_VIR], hd.dbl, NULL, 1, err) ||
            read_block(r, (size_t)hd.s[S_PRES], hd.dbl, NULL, 1, err) ||
            read_block(r, (size_t)hd.s[S_X], hd.dbl, fr->pos, 10.0f, err) ||
            read_block(r, (size_t)hd.s[S_V], hd.dbl, fr->vel, 10.0f, err) ||
            read_block(r, (size_t)hd.s[S_F], hd.dbl, NULL, 1, err))
            return MS_PLUGIN_ERROR;
        if (!hd.s[S_X]) continue; /* velocities or forces only */
        fr->has_vel = fr->vel && hd.s[S_V];
        fr->time = hd.time;
        fr->has_time = 1;
        return MS_PLUGIN_OK;
    }
}

/* ---------------------------------------------------------------- writing */

typedef struct trr_writer {
    ms_out out;
    long natoms;
    unsigned char *buf;
} trr_writer;

static void *trr_open_write(const char *path, long natoms, ms_perr *err)
{
    if (natoms < 1 || natoms > INT32_MAX / 12) {
        ms_perr_set(err, "cannot write %ld atoms to a TRR file", natoms);
        return NULL;
    }
    trr_writer *w = calloc(1, sizeof *w);
    if (!w || !(w->buf = malloc((size_t)natoms * 12))) {
        free(w);
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (ms_out_open(&w->out, path, err) != MS_PLUGIN_OK) {
        free(w->buf);
        free(w);
        return NULL;
    }
    w->natoms = natoms;
    return w;
}

static int trr_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    (void)v;
    trr_writer *w = h;
    unsigned char hd[4 * 4 + 12 + 4 * S_COUNT + 8];
    memset(hd, 0, sizeof hd);
    ms_put_be32(hd, TRR_MAGIC);
    ms_put_be32(hd + 4, 13);
    ms_put_be32(hd + 8, 12);
    memcpy(hd + 12, "GMX_trn_file", 12);
    unsigned char *s = hd + 24;
    int has_box = f->cell[0] > 0 && f->cell[1] > 0 && f->cell[2] > 0;
    ms_put_be32(s + 4 * S_BOX, has_box ? 36 : 0);
    ms_put_be32(s + 4 * S_X, (uint32_t)(w->natoms * 12));
    ms_put_be32(s + 4 * S_NATOMS, (uint32_t)w->natoms);
    ms_put_be32(s + 4 * S_STEP, (uint32_t)f->index);
    ms_put_be_float(s + 4 * S_COUNT, (float)f->time);
    ms_put_be_float(s + 4 * S_COUNT + 4, 0.0f);
    ms_out_write(&w->out, hd, 24 + 4 * S_COUNT + 8);
    if (has_box) {
        float box[9];
        unsigned char b[36];
        ms_gmx_cell_to_box(f->cell, box);
        for (int k = 0; k < 9; k++) ms_put_be_float(b + 4 * k, box[k]);
        ms_out_write(&w->out, b, 36);
    }
    for (long k = 0; k < 3 * w->natoms; k++) ms_put_be_float(w->buf + 4 * k, f->pos[k] / 10.0f);
    ms_out_write(&w->out, w->buf, (size_t)w->natoms * 12);
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int trr_close_write(void *h, ms_perr *err)
{
    trr_writer *w = h;
    int rc = ms_out_close(&w->out, err);
    free(w->buf);
    free(w);
    return rc;
}

/* Frames are found by their byte offset: the token is one. */
static int trr_tell_frame(void *h, long long *token, ms_perr *err)
{
    off_t at = ftello(((trr_reader *)h)->fp);
    if (at < 0) return ms_perr_set(err, "cannot tell the file position: %s", strerror(errno));
    *token = (long long)at;
    return MS_PLUGIN_OK;
}

static int trr_seek_frame(void *h, long long token, ms_perr *err)
{
    if (fseeko(((trr_reader *)h)->fp, (off_t)token, SEEK_SET) != 0)
        return ms_perr_set(err, "cannot seek to byte %lld: %s", token, strerror(errno));
    return MS_PLUGIN_OK;
}

static const ms_plugin trr_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "trr",
    .description = "GROMACS full-precision trajectory",
    .extensions = "trr",
    .caps = MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = trr_open_read,
    .read_frame = trr_read_frame,
    .close_read = trr_close_read,
    .tell_frame = trr_tell_frame,
    .seek_frame = trr_seek_frame,
    .open_write = trr_open_write,
    .write_frame = trr_write_frame,
    .close_write = trr_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &trr_plugin; }
