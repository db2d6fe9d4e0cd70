/* ccp4.c: the CCP4 / MRC map plugin (.ccp4, .map, .mrc): a 1024-byte header (grid counts,
 * data mode, start indices, sampling, cell, axis order, extended-header length, the MRC2000
 * origin and machine stamp), then the values with columns fastest. Reads modes 0 (int8),
 * 1 (int16), 2 (float32) and 6 (uint16) in either byte order, any axis order and skewed
 * cells; writes mode 2, little-endian, axes x y z, with the origin in the MRC origin words.
 * The origin read is the MRC origin when it is non-zero and the start indices are zero,
 * else start indices times the voxel steps (the crystallographic convention). */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define CCP4_PI 3.14159265358979323846

typedef struct ccp4_reader {
    FILE *fp;
    int swap, mode;
    long nc[3];            /* columns, rows, sections in the file */
    int axis[3];           /* which of x y z (0..2) the columns, rows, sections run along */
    long long data_at;
    ms_volume_meta meta;
} ccp4_reader;

static uint32_t bswap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

static int32_t word_i(const unsigned char *h, int w, int swap)
{
    uint32_t v;
    memcpy(&v, h + 4 * w, 4);
    return (int32_t)(swap ? bswap32(v) : v);
}

static float word_f(const unsigned char *h, int w, int swap)
{
    uint32_t v;
    memcpy(&v, h + 4 * w, 4);
    if (swap) v = bswap32(v);
    float f;
    memcpy(&f, &v, 4);
    return f;
}

static int mode_size(int mode)
{
    switch (mode) {
    case 0: return 1;
    case 1: case 6: return 2;
    case 2: return 4;
    default: return 0;
    }
}

/* A header read in byte order `swap` is plausible: known mode, positive counts, axes a
 * permutation of 1 2 3. */
static int plausible(const unsigned char *h, int swap)
{
    if (!mode_size(word_i(h, 3, swap))) return 0;
    for (int k = 0; k < 3; k++)
        if (word_i(h, k, swap) < 1) return 0;
    int seen = 0;
    for (int k = 16; k < 19; k++) {
        int a = word_i(h, k, swap);
        if (a < 1 || a > 3) return 0;
        seen |= 1 << a;
    }
    return seen == 14;
}

/* Step vectors of the cell axes (Angstrom per grid interval). */
static int cell_axes(const unsigned char *h, int swap, const long nxyz[3], double delta[3][3],
                     ms_perr *err)
{
    double len[3], ang[3];
    for (int k = 0; k < 3; k++) {
        len[k] = word_f(h, 10 + k, swap);
        ang[k] = word_f(h, 13 + k, swap);
    }
    for (int k = 0; k < 3; k++) {
        if (!(len[k] > 0 && len[k] < 1e7)) len[k] = (double)nxyz[k]; /* no cell: 1 A voxels */
        if (!(ang[k] > 0 && ang[k] < 180)) ang[k] = 90;
    }
    double ca = cos(ang[0] * CCP4_PI / 180), cb = cos(ang[1] * CCP4_PI / 180);
    double cg = cos(ang[2] * CCP4_PI / 180), sg = sin(ang[2] * CCP4_PI / 180);
    if (ang[0] == 90) ca = 0;
    if (ang[1] == 90) cb = 0;
    if (ang[2] == 90) cg = 0, sg = 1;
    double cz2 = 1 - cb * cb - ((ca - cb * cg) / sg) * ((ca - cb * cg) / sg);
    if (!(cz2 > 0)) return ms_perr_set(err, "header: impossible cell angles %g %g %g", ang[0],
                                       ang[1], ang[2]);
    double v[3][3] = {{len[0], 0, 0},
                      {len[1] * cg, len[1] * sg, 0},
                      {len[2] * cb, len[2] * (ca - cb * cg) / sg, len[2] * sqrt(cz2)}};
    for (int k = 0; k < 3; k++)
        for (int d = 0; d < 3; d++) delta[k][d] = v[k][d] / (double)nxyz[k];
    return MS_PLUGIN_OK;
}

static int parse_header(ccp4_reader *r, const unsigned char *h, long long size, ms_perr *err)
{
    int swap = !plausible(h, 0);
    if (swap && !plausible(h, 1))
        return ms_perr_set(err, "header: not a CCP4/MRC map (mode %d, size %d x %d x %d)",
                           (int)word_i(h, 3, 0), (int)word_i(h, 0, 0), (int)word_i(h, 1, 0),
                           (int)word_i(h, 2, 0));
    r->swap = swap;
    r->mode = word_i(h, 3, swap);
    long start[3], nxyz[3], n[3];
    for (int k = 0; k < 3; k++) {
        r->nc[k] = word_i(h, k, swap);
        start[k] = word_i(h, 4 + k, swap);
        nxyz[k] = word_i(h, 7 + k, swap);
        r->axis[k] = word_i(h, 16 + k, swap) - 1;
    }
    for (int k = 0; k < 3; k++) {
        n[r->axis[k]] = r->nc[k];
        if (nxyz[k] < 1) nxyz[k] = 0;
    }
    for (int k = 0; k < 3; k++)
        if (nxyz[k] == 0) nxyz[k] = n[k];   /* no sampling: one interval per point */
    long s[3];
    for (int k = 0; k < 3; k++) s[r->axis[k]] = start[k];
    int32_t nsym = word_i(h, 23, swap);
    if (nsym < 0 || nsym > size) return ms_perr_set(err, "header: bad extended header length %d", (int)nsym);
    r->data_at = 1024 + (long long)nsym;
    double points = (double)n[0] * (double)n[1] * (double)n[2];
    double need = (double)r->data_at + points * mode_size(r->mode);
    if ((double)size < need)
        return ms_perr_set(err, "header: declares %ld x %ld x %ld points of %d bytes (mode %d) "
                           "after %lld header bytes, %.0f bytes in all, but the file holds "
                           "only %lld", n[0], n[1], n[2], mode_size(r->mode), r->mode,
                           r->data_at, need, size);
    if (cell_axes(h, swap, nxyz, r->meta.delta, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    double o[3] = {word_f(h, 49, swap), word_f(h, 50, swap), word_f(h, 51, swap)};
    int use_mrc = (o[0] != 0 || o[1] != 0 || o[2] != 0) && !s[0] && !s[1] && !s[2] &&
                  isfinite(o[0]) && isfinite(o[1]) && isfinite(o[2]);
    for (int d = 0; d < 3; d++) {
        r->meta.n[d] = n[d];
        r->meta.origin[d] = use_mrc ? o[d]
                                    : s[0] * r->meta.delta[0][d] + s[1] * r->meta.delta[1][d] +
                                          s[2] * r->meta.delta[2][d];
    }
    int nlabels = word_i(h, 55, swap);
    if (nlabels > 0) {
        char label[81];
        memcpy(label, h + 224, 80);
        label[80] = '\0';
        for (int k = 79; k >= 0 && (label[k] == ' ' || label[k] == '\0'); k--) label[k] = '\0';
        for (char *c = label; *c; c++)
            if ((unsigned char)*c < 32 || (unsigned char)*c > 126) *c = ' ';
        snprintf(r->meta.name, sizeof r->meta.name, "%s", label);
    }
    return MS_PLUGIN_OK;
}

static void ccp4_close_read(void *h)
{
    ccp4_reader *r = h;
    if (r->fp) fclose(r->fp);
    free(r);
}

static void *ccp4_open_read(const char *path, long *natoms, ms_perr *err)
{
    ccp4_reader *r = calloc(1, sizeof *r);
    unsigned char h[1024];
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    long long size;
    if (!(r->fp = ms_open_sized(path, &size, err))) goto fail;
    if (fread(h, 1, sizeof h, r->fp) != sizeof h) {
        ms_perr_set(err, "header: the file ends before 1024 bytes");
        goto fail;
    }
    if (parse_header(r, h, size, err) != MS_PLUGIN_OK) goto fail;
    *natoms = 0;
    return r;
fail:
    ccp4_close_read(r);
    return NULL;
}

static int ccp4_read_volume_meta(void *h, int k, ms_volume_meta *meta, ms_perr *err)
{
    (void)err;
    ccp4_reader *r = h;
    if (k != 0) return MS_PLUGIN_EOF;
    *meta = r->meta;
    return MS_PLUGIN_OK;
}

/* One section's values (raw bytes of the file's mode) to floats. */
static void convert(const ccp4_reader *r, const unsigned char *b, float *out, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        switch (r->mode) {
        case 0: out[i] = (float)(int8_t)b[i]; break;
        case 1: case 6: {
            uint16_t v;
            memcpy(&v, b + 2 * i, 2);
            if (r->swap) v = (uint16_t)((v >> 8) | (v << 8));
            out[i] = r->mode == 1 ? (float)(int16_t)v : (float)v;
            break;
        }
        default: {
            uint32_t v;
            memcpy(&v, b + 4 * i, 4);
            if (r->swap) v = bswap32(v);
            memcpy(&out[i], &v, 4);
        }
        }
    }
}

static int ccp4_read_volume_data(void *h, int k, float *data, ms_perr *err)
{
    ccp4_reader *r = h;
    if (k != 0) return ms_perr_set(err, "no volume set %d", k);
    size_t row = (size_t)r->nc[0], bytes = row * (size_t)mode_size(r->mode);
    unsigned char *b = malloc(bytes);
    float *vals = malloc(row * sizeof *vals);
    if (!b || !vals) {
        free(b);
        free(vals);
        return ms_perr_set(err, "out of memory");
    }
    if (fseeko(r->fp, (off_t)r->data_at, SEEK_SET) != 0) {
        free(b);
        free(vals);
        return ms_perr_set(err, "cannot seek to the data");
    }
    /* Stride of each file axis in the x-fastest output. */
    size_t stride[3] = {1, (size_t)r->meta.n[0], (size_t)r->meta.n[0] * (size_t)r->meta.n[1]};
    size_t sc = stride[r->axis[0]], sr = stride[r->axis[1]], ss = stride[r->axis[2]];
    for (long s = 0; s < r->nc[2]; s++)
        for (long rr = 0; rr < r->nc[1]; rr++) {
            if (fread(b, 1, bytes, r->fp) != bytes) {
                free(b);
                free(vals);
                return ms_perr_set(err, "section %ld, row %ld: the file ends", s, rr);
            }
            convert(r, b, vals, row);
            float *d = data + (size_t)s * ss + (size_t)rr * sr;
            if (sc == 1) memcpy(d, vals, row * sizeof *vals);
            else
                for (size_t c = 0; c < row; c++) d[c * sc] = vals[c];
        }
    free(b);
    free(vals);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

static void *ccp4_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    ms_out *o = ms_out_create(sizeof *o, path, err);
    if (!o) return NULL;
    return o;
}

static void put_i(unsigned char *h, int w, int32_t v) { memcpy(h + 4 * w, &v, 4); }
static void put_f(unsigned char *h, int w, float v) { memcpy(h + 4 * w, &v, 4); }

static int ccp4_write_volume(void *h, const ms_volume_meta *m, const float *data, ms_perr *err)
{
    ms_out *o = h;
    for (int d = 0; d < 3; d++)
        if (m->n[d] < 1 || m->n[d] > INT32_MAX)
            return ms_perr_set(err, "cannot write a %ld x %ld x %ld grid", m->n[0], m->n[1], m->n[2]);
    size_t n = (size_t)m->n[0] * (size_t)m->n[1] * (size_t)m->n[2];
    unsigned char hd[1024];
    memset(hd, 0, sizeof hd);
    double len[3];
    for (int k = 0; k < 3; k++) {
        const double *v = m->delta[k];
        len[k] = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        put_i(hd, k, (int32_t)m->n[k]);
        put_i(hd, 7 + k, (int32_t)m->n[k]);
        put_f(hd, 10 + k, (float)(len[k] * (double)m->n[k]));
        put_i(hd, 16 + k, k + 1);
        put_f(hd, 49 + k, (float)m->origin[k]);
    }
    static const int pair[3][2] = {{1, 2}, {0, 2}, {0, 1}};
    for (int k = 0; k < 3; k++) {
        const double *a = m->delta[pair[k][0]], *b = m->delta[pair[k][1]];
        double la = len[pair[k][0]], lb = len[pair[k][1]], c = 0;
        if (la > 0 && lb > 0) c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
        put_f(hd, 13 + k, c == 0 ? 90.0f : (float)(acos(c > 1 ? 1 : c < -1 ? -1 : c) * 180 / CCP4_PI));
    }
    put_i(hd, 3, 2);
    float lo = n ? data[0] : 0, hi = lo;
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n; i++) {
        lo = data[i] < lo ? data[i] : lo;
        hi = data[i] > hi ? data[i] : hi;
        sum += data[i];
    }
    double mean = n ? sum / (double)n : 0;
    for (size_t i = 0; i < n; i++) sum2 += (data[i] - mean) * (data[i] - mean);
    put_f(hd, 19, lo);
    put_f(hd, 20, hi);
    put_f(hd, 21, (float)mean);
    put_i(hd, 22, 1);
    memcpy(hd + 208, "MAP ", 4);
    hd[212] = 0x44, hd[213] = 0x41; /* little-endian machine stamp */
    put_f(hd, 54, (float)sqrt(n ? sum2 / (double)n : 0));
    put_i(hd, 55, 1);
    snprintf((char *)hd + 224, 80, "%-79.79s", m->name[0] ? m->name : "written by molscope");
    uint32_t one = 1;
    unsigned char e;
    memcpy(&e, &one, 1);
    if (!e) return ms_perr_set(err, "writing CCP4 maps on a big-endian machine is not supported");
    ms_out_write(o, hd, sizeof hd);
    ms_out_write(o, data, n * sizeof *data);
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int ccp4_close_write(void *h, ms_perr *err)
{
    ms_out *o = h;
    return ms_out_destroy(o, err);
}

static const ms_plugin ccp4_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "ccp4",
    .description = "CCP4 and MRC density maps",
    .extensions = "ccp4 map mrc",
    .caps = MS_CAN_READ_VOLUME | MS_CAN_WRITE_VOLUME,
    .open_read = ccp4_open_read,
    .close_read = ccp4_close_read,
    .open_write = ccp4_open_write,
    .close_write = ccp4_close_write,
    .read_volume_meta = ccp4_read_volume_meta,
    .read_volume_data = ccp4_read_volume_data,
    .write_volume = ccp4_write_volume,
};

const ms_plugin *ms_plugin_entry(void) { return &ccp4_plugin; }
