/* xtc.c: the GROMACS XTC trajectory plugin (read only). A frame is an XDR (big-endian)
 * header (magic 1995, or 2023 for files whose frames exceed 2 GB, atom count, step, time),
 * the box (9 floats, nm), and the coordinates: up to 9 atoms as plain floats, else the
 * compressed form: a precision, the integer bounding box, an initial small-difference
 * size, and a bit stream. The stream codes each atom either as a full triple (three
 * integers packed as one mixed-radix number, or as separate bit fields when the ranges are
 * large) or, after a run flag, as a run of small differences from the atom before, the size
 * of the differences adapting from atom to atom; the first atom of a run is stored after
 * the second (water molecules compress better that way). Integers are multiplied by
 * 1/precision in single precision, then by 10 for Angstrom, exactly as GROMACS' and
 * MDAnalysis' readers do, so coordinates agree to the bit. Implemented from the format's
 * published description. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define XTC_MAGIC 1995
#define XTC_MAGIC_LARGE 2023
#define XTC_PI 3.14159265358979323846
#define FIRSTIDX 9

/* Sizes of the small-difference codes: about 2^(i/3), so three of them fit i bits. */
static const int magicints[] = {
    0,        0,        0,       0,       0,       0,       0,       0,       0,       8,
    10,       12,       16,      20,      25,      32,      40,      50,      64,      80,
    101,      128,      161,     203,     256,     322,     406,     512,     645,     812,
    1024,     1290,     1625,    2048,    2580,    3250,    4096,    5060,    6501,    8192,
    10321,    13003,    16384,   20642,   26007,   32768,   41285,   52015,   65536,   82570,
    104031,   131072,   165140,  208063,  262144,  330280,  416127,  524287,  660561,  832255,
    1048576,  1321122,  1664510, 2097152, 2642245, 3329021, 4194304, 5284491, 6658042, 8388607,
    10568983, 13316085, 16777216};
#define LASTIDX ((int)(sizeof magicints / sizeof *magicints))

typedef struct xtc_reader {
    FILE *fp;
    long natoms;
    long long size;
    long frame;            /* frames read so far */
    unsigned char *buf;    /* compressed bytes of one frame */
    size_t buf_cap;
    int32_t *ints;         /* 3 per atom */
    size_t ints_cap;
} xtc_reader;

/* ---------------------------------------------------------------- XDR input */

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static float be_float(const unsigned char *p)
{
    uint32_t v = be32(p);
    float f;
    memcpy(&f, &v, 4);
    return f;
}

/* Read n bytes; 0 at a clean end of file before any byte, 1 when all read, -1 short. */
static int read_exact(FILE *fp, void *b, size_t n)
{
    size_t got = fread(b, 1, n, fp);
    if (got == n) return 1;
    return got == 0 && feof(fp) ? 0 : -1;
}

/* ---------------------------------------------------------------- bit stream */

typedef struct bits {
    const unsigned char *p, *end;
    uint64_t acc;          /* the low `n` bits are unread, most significant first */
    int n;
    int overrun;
} bits;

static inline uint32_t get_bits(bits *b, int n)
{
    if (b->n < n) {
        while (b->n <= 56) {
            if (b->p < b->end) b->acc = (b->acc << 8) | *b->p++;
            else if (b->n >= n) break;
            else {
                b->acc <<= 8;
                b->overrun = 1;
            }
            b->n += 8;
        }
    }
    b->n -= n;
    return (uint32_t)(b->acc >> b->n) & (uint32_t)((1ull << n) - 1);
}

/* Up to 56 bits, most significant first. */
static inline uint64_t get_bits56(bits *b, int n)
{
    if (b->n < n) {
        while (b->n <= 56) {
            if (b->p < b->end) b->acc = (b->acc << 8) | *b->p++;
            else if (b->n >= n) break;
            else {
                b->acc <<= 8;
                b->overrun = 1;
            }
            b->n += 8;
        }
    }
    b->n -= n;
    return (b->acc >> b->n) & ((1ull << n) - 1);
}

/* Three integers packed as one number of nbits bits in the radices sizes[] (the first
 * coordinate most significant). The bits come in bytes, least significant byte first, each
 * byte most significant bit first, the last byte holding the 1..8 bits left: the full bytes
 * are read in one go and byte-reversed. */
static inline void get_ints(bits *b, int nbits, const uint32_t sizes[3], int32_t out[3])
{
    if (nbits <= 64) {
        int full = (nbits - 1) / 8, rest = nbits - 8 * full;
        uint64_t v = 0;
        if (full) v = __builtin_bswap64(get_bits56(b, 8 * full)) >> (64 - 8 * full);
        v |= (uint64_t)get_bits(b, rest) << (8 * full);
        if (v >> 32 == 0) {
            uint32_t w = (uint32_t)v;
            out[2] = (int32_t)(w % sizes[2]);
            w /= sizes[2];
            out[1] = (int32_t)(w % sizes[1]);
            out[0] = (int32_t)(w / sizes[1]);
            return;
        }
        out[2] = (int32_t)(v % sizes[2]);
        v /= sizes[2];
        out[1] = (int32_t)(v % sizes[1]);
        out[0] = (int32_t)(v / sizes[1]);
        return;
    }
    unsigned __int128 v = 0;
    int shift = 0;
    while (nbits > 8) {
        v |= (unsigned __int128)get_bits(b, 8) << shift;
        shift += 8;
        nbits -= 8;
    }
    if (nbits > 0) v |= (unsigned __int128)get_bits(b, nbits) << shift;
    out[2] = (int32_t)(v % sizes[2]);
    v /= sizes[2];
    out[1] = (int32_t)(v % sizes[1]);
    out[0] = (int32_t)(v / sizes[1]);
}

/* Bits needed for values up to `size` (the count of bits of size). */
static int bits_of(uint64_t size)
{
    int n = 0;
    while (n < 64 && size >= (1ull << n)) n++;
    return n;
}

/* Bits of the product of three sizes (as the format counts them: of the product itself). */
static int bits_of_product(const uint32_t s[3])
{
    unsigned __int128 p = (unsigned __int128)s[0] * s[1] * s[2];
    int n = 0;
    while (p) {
        n++;
        p >>= 1;
    }
    return n;
}

/* ---------------------------------------------------------------- decoding */

typedef struct xtc_head {
    float precision;
    int32_t minint[3], maxint[3], smallidx;
} xtc_head;

/* Decode natoms integer triples from the stream into ip. */
static int decode(const xtc_head *h, const unsigned char *data, size_t len, long natoms,
                  int32_t *ip, ms_perr *err)
{
    uint32_t sizeint[3], sizesmall[3];
    int bitsizeint[3] = {0, 0, 0}, bitsize = 0, large = 0;
    for (int d = 0; d < 3; d++) {
        int64_t s = (int64_t)h->maxint[d] - h->minint[d] + 1;
        if (s < 1 || s > 0xffffffffLL)
            return ms_perr_set(err, "bad coordinate range %d..%d", (int)h->minint[d],
                               (int)h->maxint[d]);
        sizeint[d] = (uint32_t)s;
        if (s > 0xffffff) large = 1;
    }
    if (large)
        for (int d = 0; d < 3; d++) bitsizeint[d] = bits_of(sizeint[d]);
    else
        bitsize = bits_of_product(sizeint);
    int smallidx = h->smallidx;
    if (smallidx < FIRSTIDX || smallidx >= LASTIDX)
        return ms_perr_set(err, "bad small-difference size index %d", smallidx);
    int smaller = magicints[smallidx - 1 > FIRSTIDX ? smallidx - 1 : FIRSTIDX] / 2;
    int smallnum = magicints[smallidx] / 2;
    sizesmall[0] = sizesmall[1] = sizesmall[2] = (uint32_t)magicints[smallidx];
    bits b = {data, data + len, 0, 0, 0};
    long i = 0;
    int run = 0;
    while (i < natoms) {
        int32_t *t = ip + 3 * i, prev[3];
        if (large)
            for (int d = 0; d < 3; d++) t[d] = (int32_t)get_bits(&b, bitsizeint[d]);
        else
            get_ints(&b, bitsize, sizeint, t);
        i++;
        for (int d = 0; d < 3; d++) prev[d] = t[d] = (int32_t)((uint32_t)t[d] + (uint32_t)h->minint[d]);
        int is_smaller = 0;
        if (get_bits(&b, 1)) {
            run = (int)get_bits(&b, 5);
            is_smaller = run % 3;
            run -= is_smaller;
            is_smaller--;
        }
        if (run > 0) {
            if (i + run / 3 > natoms)
                return ms_perr_set(err, "a run of %d atoms passes the atom count %ld", run / 3,
                                   natoms);
            t += 3;
            for (int k = 0; k < run; k += 3, t += 3) {
                get_ints(&b, smallidx, sizesmall, t);
                i++;
                for (int d = 0; d < 3; d++)
                    t[d] = (int32_t)((uint32_t)t[d] + (uint32_t)prev[d] - (uint32_t)smallnum);
                if (k == 0) {
                    /* The first atom of a run was stored second: swap them back. */
                    for (int d = 0; d < 3; d++) {
                        int32_t tmp = t[d];
                        t[d] = prev[d];
                        prev[d] = tmp;
                        t[d - 3] = prev[d];
                    }
                } else {
                    memcpy(prev, t, sizeof prev);
                }
            }
        }
        smallidx += is_smaller;
        if (smallidx < FIRSTIDX || smallidx >= LASTIDX)
            return ms_perr_set(err, "atom %ld: bad small-difference size index %d", i, smallidx);
        if (is_smaller < 0) {
            smallnum = smaller;
            smaller = smallidx > FIRSTIDX ? magicints[smallidx - 1] / 2 : 0;
        } else if (is_smaller > 0) {
            smaller = smallnum;
            smallnum = magicints[smallidx] / 2;
        }
        sizesmall[0] = sizesmall[1] = sizesmall[2] = (uint32_t)magicints[smallidx];
        if (b.overrun) return ms_perr_set(err, "the compressed coordinates end early");
    }
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- frames */

static void xtc_close_read(void *h)
{
    xtc_reader *r = h;
    if (r->fp) fclose(r->fp);
    free(r->buf);
    free(r->ints);
    free(r);
}

static void *xtc_open_read(const char *path, long *natoms, ms_perr *err)
{
    xtc_reader *r = calloc(1, sizeof *r);
    unsigned char h[16];
    struct stat sb;
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (!(r->fp = fopen(path, "rb")) || fstat(fileno(r->fp), &sb) != 0) {
        ms_perr_set(err, "%s", strerror(errno));
        goto fail;
    }
    r->size = (long long)sb.st_size;
    if (read_exact(r->fp, h, 16) != 1) {
        ms_perr_set(err, "not an XTC file: shorter than a frame header");
        goto fail;
    }
    int32_t magic = (int32_t)be32(h), n = (int32_t)be32(h + 4);
    if (magic != XTC_MAGIC && magic != XTC_MAGIC_LARGE) {
        ms_perr_set(err, "not an XTC file: magic number %d, expected 1995", (int)magic);
        goto fail;
    }
    /* Every atom takes at least a few bits: refuse counts the file cannot hold. */
    if (n < 1 || (double)n > 8.0 * (double)r->size + 16) {
        ms_perr_set(err, "frame 0: bad atom count %d", (int)n);
        goto fail;
    }
    rewind(r->fp);
    r->natoms = n;
    *natoms = n;
    return r;
fail:
    xtc_close_read(r);
    return NULL;
}

/* Box vectors (nm) -> a b c (Angstrom) alpha beta gamma (degrees). */
static void box_to_cell(const float v[9], float cell[6])
{
    double len[3];
    for (int k = 0; k < 3; k++)
        len[k] = sqrt((double)v[3 * k] * v[3 * k] + (double)v[3 * k + 1] * v[3 * k + 1] +
                      (double)v[3 * k + 2] * v[3 * k + 2]);
    static const int pair[3][2] = {{1, 2}, {0, 2}, {0, 1}};
    for (int k = 0; k < 3; k++) {
        const float *a = v + 3 * pair[k][0], *b = v + 3 * pair[k][1];
        double la = len[pair[k][0]], lb = len[pair[k][1]], ang = 90.0;
        if (la > 0 && lb > 0) {
            double c = ((double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]) / (la * lb);
            ang = c == 0 ? 90.0 : acos(c > 1 ? 1 : c < -1 ? -1 : c) * 180.0 / XTC_PI;
        }
        cell[k] = (float)(10.0 * len[k]);
        cell[3 + k] = (float)ang;
    }
}

static int grow_buf(xtc_reader *r, size_t bytes, ms_perr *err)
{
    if (bytes <= r->buf_cap) return MS_PLUGIN_OK;
    unsigned char *b = realloc(r->buf, bytes);
    if (!b) return ms_perr_set(err, "out of memory for %zu bytes", bytes);
    r->buf = b;
    r->buf_cap = bytes;
    return MS_PLUGIN_OK;
}

/* The compressed coordinates of a frame of more than 9 atoms. */
static int read_compressed(xtc_reader *r, int large, long n, ms_frame_out *fr, ms_perr *err)
{
    unsigned char h[44];
    if (read_exact(r->fp, h, large ? 40 : 36) != 1)
        return ms_perr_set(err, "truncated: the file ends in the coordinate header");
    xtc_head head;
    head.precision = be_float(h);
    for (int d = 0; d < 3; d++) {
        head.minint[d] = (int32_t)be32(h + 4 + 4 * d);
        head.maxint[d] = (int32_t)be32(h + 16 + 4 * d);
    }
    head.smallidx = (int32_t)be32(h + 28);
    uint64_t bytes = large ? ((uint64_t)be32(h + 32) << 32 | be32(h + 36)) : be32(h + 32);
    if (bytes > (uint64_t)r->size)
        return ms_perr_set(err, "bad compressed size %llu bytes", (unsigned long long)bytes);
    size_t padded = (size_t)((bytes + 3) & ~(uint64_t)3);
    if (!fr->pos) /* skipped frame */
        return fseeko(r->fp, (off_t)padded, SEEK_CUR) == 0 ? MS_PLUGIN_OK
                                                            : ms_perr_set(err, "seek failed");
    if (!(head.precision > 0) || !isfinite(head.precision))
        return ms_perr_set(err, "bad precision %g", (double)head.precision);
    if (grow_buf(r, padded, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    if (read_exact(r->fp, r->buf, padded) != 1)
        return ms_perr_set(err, "truncated: the file ends in the compressed coordinates");
    if ((size_t)n * 3 > r->ints_cap) {
        int32_t *ni = realloc(r->ints, (size_t)n * 3 * sizeof *ni);
        if (!ni) return ms_perr_set(err, "out of memory");
        r->ints = ni;
        r->ints_cap = (size_t)n * 3;
    }
    if (decode(&head, r->buf, (size_t)bytes, n, r->ints, err) != MS_PLUGIN_OK)
        return MS_PLUGIN_ERROR;
    float inv = (float)(1.0 / (double)head.precision);
    for (size_t k = 0; k < (size_t)n * 3; k++) {
        float nm = (float)r->ints[k] * inv;
        fr->pos[k] = nm * 10.0f;
    }
    return MS_PLUGIN_OK;
}

static int xtc_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    xtc_reader *r = h;
    unsigned char b[56];
    int got = read_exact(r->fp, b, 56);
    if (got == 0) return MS_PLUGIN_EOF;
    if (got < 0) return ms_perr_set(err, "truncated: the file ends in the frame header");
    int32_t magic = (int32_t)be32(b), n = (int32_t)be32(b + 4), step = (int32_t)be32(b + 8);
    (void)step;
    if (magic != XTC_MAGIC && magic != XTC_MAGIC_LARGE)
        return ms_perr_set(err, "bad magic number %d at byte %lld", (int)magic,
                           (long long)ftello(r->fp) - 56);
    if (n != natoms || (int32_t)be32(b + 52) != n)
        return ms_perr_set(err, "the frame has %d atoms, expected %ld", (int)n, natoms);
    fr->time = be_float(b + 12);
    fr->has_time = 1;
    float box[9];
    for (int k = 0; k < 9; k++) box[k] = be_float(b + 16 + 4 * k);
    box_to_cell(box, fr->cell);
    fr->has_cell = 1;
    r->frame++;
    if (n > 9) return read_compressed(r, magic == XTC_MAGIC_LARGE, n, fr, err);
    unsigned char p[9 * 12];
    if (read_exact(r->fp, p, (size_t)n * 12) != 1)
        return ms_perr_set(err, "truncated: the file ends in the coordinates");
    for (long k = 0; fr->pos && k < 3 * (long)n; k++) fr->pos[k] = be_float(p + 4 * k) * 10.0f;
    return MS_PLUGIN_OK;
}

static const ms_plugin xtc_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "xtc",
    .description = "GROMACS compressed trajectory",
    .extensions = "xtc",
    .caps = MS_CAN_READ_FRAMES,
    .open_read = xtc_open_read,
    .read_frame = xtc_read_frame,
    .close_read = xtc_close_read,
};

const ms_plugin *ms_plugin_entry(void) { return &xtc_plugin; }
