/* xtc.c: the GROMACS XTC trajectory plugin (read and write). A frame is an XDR (big-endian)
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
 * published description.
 *
 * Writing: precision 1000 (GROMACS' default), coordinates rounded to the nearest integer
 * (half away from zero); the encoder mirrors the decoder (the same size table and range
 * rules) and chooses its own runs and size changes (see encode).
 *
 * Speed: the stream is read 64 bits at a time, the small differences are split by
 * multiplying with precomputed reciprocals instead of dividing, and each atom goes straight
 * from its integers to the caller's floats. A frame's stream can only be decoded from its
 * start, so frames are decoded in parallel instead: once the host reads consecutive frames
 * of a large system (10000 atoms or more), the reader reads the next frames' compressed
 * bytes ahead and worker threads decode them into buffers of their own while the host's
 * thread stores the current frame; a frame no worker has begun when the host asks for it
 * is decoded by the host's thread straight into the host's array, and while a worker
 * finishes the frame asked for, the host's thread decodes a later one. Threads: one per
 * core the load average leaves idle, the host's included (at most 9); MOLSCOPE_THREADS
 * sets the count, 1 turns reading ahead off. Reading ahead stops while the host skips frames (every second frame or
 * sparser is read as before, seeking past the others); frames read ahead take at most
 * XTC_AHEAD_BYTES of memory. */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "gmx_util.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define XTC_MAGIC 1995
#define XTC_MAGIC_LARGE 2023
#define FIRSTIDX 9
#define XTC_AHEAD_MIN_ATOMS 10000
#define XTC_MAX_WORKERS 8
#define XTC_AHEAD_BYTES ((size_t)1 << 30)

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

typedef struct xtc_head {
    float precision;
    int32_t minint[3], maxint[3], smallidx;
} xtc_head;

/* One frame as read from the file, before decoding. */
typedef struct xtc_frame {
    int rc;                /* MS_PLUGIN_OK, _EOF or _ERROR (err says why) */
    ms_perr err;
    double time;
    float cell[6];
    int compressed;        /* else plain[] holds the coordinates (9 atoms at most) */
    xtc_head head;
    size_t bytes;          /* of the compressed stream */
    unsigned char *buf;    /* the stream (padded to 4 bytes) */
    size_t buf_cap;
    float plain[27];
    /* frames read ahead */
    long long at;          /* the frame's file offset */
    int state;             /* S_READ, S_BUSY, S_DONE */
    long natoms;
    float *pos;            /* decoded coordinates */
    size_t pos_cap;
} xtc_frame;

enum { S_READ, S_BUSY, S_DONE };

/* Frames read ahead: frame k of [head, tail) is slot k % nslots; workers decode them in
 * order (next: the first not taken). */
typedef struct xtc_ahead {
    pthread_mutex_t mu;
    pthread_cond_t work, done;
    pthread_t th[XTC_MAX_WORKERS];
    int nthreads, nslots, stop, ended;
    long head, tail, next, natoms;
    xtc_frame slot[XTC_MAX_WORKERS + 2];
} xtc_ahead;

typedef struct xtc_reader {
    FILE *fp;
    long natoms;
    long long size;
    xtc_frame sync;        /* the frame read without reading ahead */
    xtc_ahead *ahead;      /* NULL until the host streams a large system */
    int no_ahead;          /* reading ahead is off, or could not start */
    int kept;              /* the host wanted the last frame's coordinates */
} xtc_reader;

/* ---------------------------------------------------------------- XDR input */

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
    int overrun;           /* the stream ended: zeros were read past it */
} bits;

/* At least `want` (<= 56) unread bits: whole bytes, eight at a time where the stream has
 * them. */
static inline void refill(bits *b, int want)
{
    if (b->end - b->p >= 8) {
        uint64_t w;
        memcpy(&w, b->p, 8);
        w = __builtin_bswap64(w);
        int k = (63 - b->n) >> 3;
        b->acc = (b->acc << (8 * k)) | (w >> (64 - 8 * k));
        b->p += k;
        b->n += 8 * k;
        return;
    }
    while (b->n <= 56) {
        if (b->p < b->end) b->acc = (b->acc << 8) | *b->p++;
        else if (b->n >= want) break;
        else {
            b->acc <<= 8;
            b->overrun = 1;
        }
        b->n += 8;
    }
}

/* The next n (<= 56) bits, most significant first. */
static inline uint64_t get_bits(bits *b, int n)
{
    if (b->n < n) refill(b, n);
    b->n -= n;
    return (b->acc >> b->n) & ((1ull << n) - 1);
}

/* A number of nbits (<= 64) bits stored as bytes least significant first, each byte most
 * significant bit first, the last byte holding the 1..8 bits left: the full bytes are read
 * in one go and byte-reversed. */
static inline uint64_t get_packed(bits *b, int nbits)
{
    int full = (nbits - 1) / 8, rest = nbits - 8 * full;
    uint64_t v = 0;
    if (full) v = __builtin_bswap64(get_bits(b, 8 * full)) >> (64 - 8 * full);
    return v | get_bits(b, rest) << (8 * full);
}

/* ---------------------------------------------------------------- splitting numbers */

/* x / d for a 32-bit x and a d >= 2 as a product with the reciprocal m = 2^64 / d rounded
 * up: exact for every 32-bit x (Lemire, Kaser and Kurz, "Faster remainder by direct
 * computation", 2019). */
typedef struct recip {
    uint64_t m;
    uint32_t d;
} recip;

static inline recip recip_of(uint32_t d)
{
    recip r = {UINT64_MAX / d + 1, d};
    return r;
}

static inline uint32_t recip_div(uint32_t x, recip r)
{
    return (uint32_t)(((unsigned __int128)r.m * x) >> 64);
}

/* Three integers packed as one number of more than 64 bits in the radices sizes[] (the
 * first coordinate most significant). */
static void get_ints_wide(bits *b, int nbits, const uint32_t sizes[3], int32_t out[3])
{
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

/* v / r.d into *q, the remainder returned: by the reciprocal when v and r.d allow. */
static inline uint32_t split(uint64_t v, recip r, uint64_t *q)
{
    if (v >> 32 == 0 && r.d > 1) {
        uint32_t w = (uint32_t)v, d = recip_div(w, r);
        *q = d;
        return w - d * r.d;
    }
    *q = v / r.d;
    return (uint32_t)(v % r.d);
}

/* Three integers packed as one number of nbits bits in the radices r[].d, plus min[]. */
static inline void get_ints(bits *b, int nbits, const recip r[3], const int32_t min[3],
                            int32_t out[3])
{
    uint32_t v[3];
    if (nbits > 64) {
        uint32_t s[3] = {r[0].d, r[1].d, r[2].d};
        get_ints_wide(b, nbits, s, (int32_t *)v);
    } else {
        uint64_t q, q2;
        v[2] = split(get_packed(b, nbits), r[2], &q);
        v[1] = split(q, r[1], &q2);
        v[0] = (uint32_t)q2;
    }
    out[0] = (int32_t)(v[0] + (uint32_t)min[0]);
    out[1] = (int32_t)(v[1] + (uint32_t)min[1]);
    out[2] = (int32_t)(v[2] + (uint32_t)min[2]);
}

/* Three small differences of one size r.d packed in nbits bits. */
static inline void get_small(bits *b, int nbits, recip r, int32_t out[3])
{
    if (nbits > 32) {
        uint32_t s[3] = {r.d, r.d, r.d};
        get_ints_wide(b, nbits, s, out);
        return;
    }
    uint32_t v = (uint32_t)get_packed(b, nbits), q = recip_div(v, r), q2 = recip_div(q, r);
    out[2] = (int32_t)(v - q * r.d);
    out[1] = (int32_t)(q - q2 * r.d);
    out[0] = (int32_t)q2;
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

/* Sizes of the full triples: packed together (*bitsize) or, for large ranges, in separate
 * fields (bitsizeint[]). The encoder sizes its triples with the same rule. */
static int full_sizes(const xtc_head *h, uint32_t sizeint[3], int bitsizeint[3], int *bitsize,
                      int *large, ms_perr *err)
{
    *large = 0;
    for (int d = 0; d < 3; d++) {
        int64_t s = (int64_t)h->maxint[d] - h->minint[d] + 1;
        if (s < 1 || s > 0xffffffffLL)
            return ms_perr_set(err, "bad coordinate range %d..%d", (int)h->minint[d],
                               (int)h->maxint[d]);
        sizeint[d] = (uint32_t)s;
        if (s > 0xffffff) *large = 1;
    }
    *bitsize = 0;
    for (int d = 0; d < 3; d++) bitsizeint[d] = *large ? bits_of(sizeint[d]) : 0;
    if (!*large) *bitsize = bits_of_product(sizeint);
    return MS_PLUGIN_OK;
}

/* An atom's integers to Angstrom: times 1/precision in single precision, then times 10. */
static inline void put_atom(float *p, const int32_t v[3], float inv)
{
    for (int d = 0; d < 3; d++) {
        float nm = (float)v[d] * inv;
        p[d] = nm * 10.0f;
    }
}

/* A run of small differences following the atom `full` (its integers), whose coordinates
 * go to p: the run's first atom was stored before `full` (water molecules compress better
 * that way), so it goes to p and `full` after it. Returns the atoms written. */
static long small_run(bits *b, int run, int smallidx, recip r, int smallnum,
                      const int32_t full[3], float inv, float *p)
{
    int32_t prev[3] = {full[0], full[1], full[2]};
    for (int k = 0; k < run; k += 3) {
        int32_t s[3];
        get_small(b, smallidx, r, s);
        for (int d = 0; d < 3; d++)
            prev[d] = (int32_t)((uint32_t)s[d] + (uint32_t)prev[d] - (uint32_t)smallnum);
        put_atom(p, prev, inv);
        p += 3;
        if (k == 0) {
            put_atom(p, full, inv);
            p += 3;
        }
    }
    return run / 3 + 1;
}

/* Decode natoms atoms from the stream into pos (3 floats each, Angstrom). */
static int decode(const xtc_head *h, const unsigned char *data, size_t len, long natoms,
                  float *pos, ms_perr *err)
{
    uint32_t sizeint[3];
    int bitsizeint[3], bitsize = 0, large;
    if (full_sizes(h, sizeint, bitsizeint, &bitsize, &large, err) != MS_PLUGIN_OK)
        return MS_PLUGIN_ERROR;
    int smallidx = h->smallidx;
    if (smallidx < FIRSTIDX || smallidx >= LASTIDX)
        return ms_perr_set(err, "bad small-difference size index %d", smallidx);
    recip rs[LASTIDX], rfull[3];
    for (int k = FIRSTIDX; k < LASTIDX; k++) rs[k] = recip_of((uint32_t)magicints[k]);
    for (int d = 0; d < 3; d++) rfull[d] = recip_of(sizeint[d]);
    if (!len) return ms_perr_set(err, "no compressed coordinates for %ld atoms", natoms);
    float inv = (float)(1.0 / (double)h->precision);
    int smaller = magicints[smallidx - 1 > FIRSTIDX ? smallidx - 1 : FIRSTIDX] / 2;
    int smallnum = magicints[smallidx] / 2;
    bits b = {data, data + len, 0, 0, 0};
    long i = 0;
    int run = 0;
    while (i < natoms) {
        int32_t t[3];
        if (large)
            for (int d = 0; d < 3; d++)
                t[d] = (int32_t)((uint32_t)get_bits(&b, bitsizeint[d]) + (uint32_t)h->minint[d]);
        else
            get_ints(&b, bitsize, rfull, h->minint, t);
        int is_smaller = 0;
        if (get_bits(&b, 1)) {
            run = (int)get_bits(&b, 5);
            is_smaller = run % 3;
            run -= is_smaller;
            is_smaller--;
        }
        if (run > 0) {
            if (i + 1 + run / 3 > natoms)
                return ms_perr_set(err, "a run of %d atoms passes the atom count %ld", run / 3,
                                   natoms);
            i += small_run(&b, run, smallidx, rs[smallidx], smallnum, t, inv, pos + 3 * i);
        } else {
            put_atom(pos + 3 * i++, t, inv);
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
        if (b.overrun) return ms_perr_set(err, "the compressed coordinates end early");
    }
    return MS_PLUGIN_OK;
}

/* Decode a frame's stream into pos (3 natoms floats). */
static int decode_frame(const xtc_frame *f, long natoms, float *pos, ms_perr *err)
{
    return decode(&f->head, f->buf, f->bytes, natoms, pos, err);
}

/* ---------------------------------------------------------------- reading frames */

static int grow_buf(xtc_frame *f, size_t bytes, ms_perr *err)
{
    if (bytes <= f->buf_cap) return MS_PLUGIN_OK;
    unsigned char *b = realloc(f->buf, bytes);
    if (!b) return ms_perr_set(err, "out of memory for %zu bytes", bytes);
    f->buf = b;
    f->buf_cap = bytes;
    return MS_PLUGIN_OK;
}

/* The compressed coordinates' header and stream (skipped when !keep). */
static int read_stream(xtc_reader *r, xtc_frame *f, int large, int keep, ms_perr *err)
{
    unsigned char h[44];
    if (read_exact(r->fp, h, large ? 40 : 36) != 1)
        return ms_perr_set(err, "truncated: the file ends in the coordinate header");
    f->head.precision = ms_be_float(h);
    for (int d = 0; d < 3; d++) {
        f->head.minint[d] = (int32_t)ms_be32(h + 4 + 4 * d);
        f->head.maxint[d] = (int32_t)ms_be32(h + 16 + 4 * d);
    }
    f->head.smallidx = (int32_t)ms_be32(h + 28);
    uint64_t bytes = large ? ((uint64_t)ms_be32(h + 32) << 32 | ms_be32(h + 36)) : ms_be32(h + 32);
    if (bytes > (uint64_t)r->size)
        return ms_perr_set(err, "bad compressed size %llu bytes", (unsigned long long)bytes);
    size_t padded = (size_t)((bytes + 3) & ~(uint64_t)3);
    f->bytes = (size_t)bytes;
    if (!keep)
        return fseeko(r->fp, (off_t)padded, SEEK_CUR) == 0 ? MS_PLUGIN_OK
                                                            : ms_perr_set(err, "seek failed");
    if (!(f->head.precision > 0) || !isfinite(f->head.precision))
        return ms_perr_set(err, "bad precision %g", (double)f->head.precision);
    if (grow_buf(f, padded, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    if (read_exact(r->fp, f->buf, padded) != 1)
        return ms_perr_set(err, "truncated: the file ends in the compressed coordinates");
    return MS_PLUGIN_OK;
}

/* Read the next frame of natoms atoms from the file into f, up to decoding (the stream is
 * skipped when !keep). */
static int read_raw(xtc_reader *r, xtc_frame *f, long natoms, int keep, ms_perr *err)
{
    unsigned char b[56];
    int got = read_exact(r->fp, b, 56);
    if (got == 0) return MS_PLUGIN_EOF;
    if (got < 0) return ms_perr_set(err, "truncated: the file ends in the frame header");
    int32_t magic = (int32_t)ms_be32(b), n = (int32_t)ms_be32(b + 4);
    if (magic != XTC_MAGIC && magic != XTC_MAGIC_LARGE)
        return ms_perr_set(err, "bad magic number %d at byte %lld", (int)magic,
                           (long long)ftello(r->fp) - 56);
    if (n != natoms || (int32_t)ms_be32(b + 52) != n)
        return ms_perr_set(err, "the frame has %d atoms, expected %ld", (int)n, natoms);
    f->time = ms_be_float(b + 12);
    double box[9];
    for (int k = 0; k < 9; k++) box[k] = ms_be_float(b + 16 + 4 * k);
    ms_gmx_box_to_cell(box, f->cell);
    f->compressed = n > 9;
    if (f->compressed) return read_stream(r, f, magic == XTC_MAGIC_LARGE, keep, err);
    unsigned char p[9 * 12];
    if (read_exact(r->fp, p, (size_t)n * 12) != 1)
        return ms_perr_set(err, "truncated: the file ends in the coordinates");
    for (long k = 0; k < 3 * (long)n; k++) f->plain[k] = ms_be_float(p + 4 * k) * 10.0f;
    return MS_PLUGIN_OK;
}

/* The frame's time, cell and coordinates (when the host wants them) into fr. */
static int finish(const xtc_frame *f, long natoms, ms_frame_out *fr, ms_perr *err)
{
    fr->time = f->time;
    fr->has_time = 1;
    memcpy(fr->cell, f->cell, sizeof fr->cell);
    fr->has_cell = 1;
    if (!fr->pos) return MS_PLUGIN_OK;
    if (f->compressed) return decode_frame(f, natoms, fr->pos, err);
    memcpy(fr->pos, f->plain, (size_t)natoms * 3 * sizeof *fr->pos);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- reading ahead */

/* Decode a frame read ahead into its own coordinate array. */
static void decode_ahead(xtc_frame *f)
{
    size_t n = (size_t)f->natoms * 3;
    if (n > f->pos_cap) {
        float *p = realloc(f->pos, n * sizeof *p);
        if (!p) {
            f->rc = ms_perr_set(&f->err, "out of memory for %zu coordinates", n);
            return;
        }
        f->pos = p;
        f->pos_cap = n;
    }
    f->rc = decode_frame(f, f->natoms, f->pos, &f->err);
}

/* The next frame read ahead that no thread decodes yet, claimed; NULL when there is none.
 * Called under the lock. */
static xtc_frame *claim_next(xtc_ahead *a)
{
    while (a->next < a->tail) {
        xtc_frame *f = &a->slot[a->next++ % a->nslots];
        if (f->state == S_READ) {
            f->state = S_BUSY;
            return f;
        }
    }
    return NULL;
}

/* Decode a claimed frame into its slot: the lock is held on entry and on return. */
static void decode_claimed(xtc_ahead *a, xtc_frame *f)
{
    pthread_mutex_unlock(&a->mu);
    decode_ahead(f);
    pthread_mutex_lock(&a->mu);
    f->state = S_DONE;
    pthread_cond_broadcast(&a->done);
}

static void *worker(void *arg)
{
    xtc_ahead *a = arg;
    pthread_mutex_lock(&a->mu);
    while (!a->stop) {
        xtc_frame *f = claim_next(a);
        if (f) decode_claimed(a, f);
        else pthread_cond_wait(&a->work, &a->mu);
    }
    pthread_mutex_unlock(&a->mu);
    return NULL;
}

/* Threads decoding (the host's thread is one of them): MOLSCOPE_THREADS, else the cores
 * online that the load average leaves idle (on a machine whose cores are all busy, more
 * threads only wait for each other), at most XTC_MAX_WORKERS + 1. */
static int thread_count(void)
{
    const char *e = getenv("MOLSCOPE_THREADS");
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    double load;
    if (e && *e) n = strtol(e, NULL, 10);
    else if (getloadavg(&load, 1) == 1 && load > 0) n = (long)((double)n - load + 0.5);
    return n < 1 ? 1 : n > XTC_MAX_WORKERS + 1 ? XTC_MAX_WORKERS + 1 : (int)n;
}

static void ahead_stop(xtc_ahead *a)
{
    pthread_mutex_lock(&a->mu);
    a->stop = 1;
    pthread_cond_broadcast(&a->work);
    pthread_mutex_unlock(&a->mu);
    for (int k = 0; k < a->nthreads; k++) pthread_join(a->th[k], NULL);
    for (int k = 0; k < a->nslots; k++) {
        free(a->slot[k].buf);
        free(a->slot[k].pos);
    }
    pthread_mutex_destroy(&a->mu);
    pthread_cond_destroy(&a->work);
    pthread_cond_destroy(&a->done);
    free(a);
}

/* Start reading ahead frames of natoms atoms, NULL when it would not help (one core, a
 * small system, too little memory for two frames) or cannot start. */
static xtc_ahead *ahead_start(long natoms)
{
    int workers = thread_count() - 1;
    size_t frame = (size_t)natoms * 16;   /* coordinates and a generous stream */
    size_t slots = XTC_AHEAD_BYTES / (frame ? frame : 1);
    if (slots > (size_t)workers + 3) slots = (size_t)workers + 3;
    if (workers < 1 || natoms < XTC_AHEAD_MIN_ATOMS || slots < 2) return NULL;
    xtc_ahead *a = calloc(1, sizeof *a);
    if (!a) return NULL;
    a->nslots = (int)slots;
    a->natoms = natoms;
    pthread_mutex_init(&a->mu, NULL);
    pthread_cond_init(&a->work, NULL);
    pthread_cond_init(&a->done, NULL);
    while (a->nthreads < workers && a->nthreads < a->nslots &&
           pthread_create(&a->th[a->nthreads], NULL, worker, a) == 0)
        a->nthreads++;
    if (a->nthreads == 0) {
        ahead_stop(a);
        return NULL;
    }
    return a;
}

/* Read frames into every free slot and hand them to the workers. */
static void ahead_fill(xtc_reader *r)
{
    xtc_ahead *a = r->ahead;
    while (!a->ended && a->tail - a->head < a->nslots) {
        xtc_frame *f = &a->slot[a->tail % a->nslots];
        f->natoms = a->natoms;
        f->err.msg[0] = '\0';
        f->at = (long long)ftello(r->fp);
        f->rc = read_raw(r, f, a->natoms, 1, &f->err);
        if (f->rc != MS_PLUGIN_OK) a->ended = 1;
        pthread_mutex_lock(&a->mu);
        f->state = f->rc == MS_PLUGIN_OK && f->compressed ? S_READ : S_DONE;
        a->tail++;
        pthread_cond_signal(&a->work);
        pthread_mutex_unlock(&a->mu);
    }
}

/* A frame a worker decoded: its data into fr. */
static int deliver(const xtc_frame *f, long natoms, ms_frame_out *fr, ms_perr *err)
{
    if (f->rc != MS_PLUGIN_OK) {
        *err = f->err;
        return f->rc;
    }
    fr->time = f->time;
    fr->has_time = 1;
    memcpy(fr->cell, f->cell, sizeof fr->cell);
    fr->has_cell = 1;
    if (fr->pos)
        memcpy(fr->pos, f->compressed ? f->pos : f->plain, (size_t)natoms * 3 * sizeof *fr->pos);
    return MS_PLUGIN_OK;
}

/* The next frame from the frames read ahead. When no thread has begun it, the host's
 * thread decodes it straight into the host's array (no copy); while a worker is on it, the
 * host's thread decodes a later frame meanwhile. */
static int from_ahead(xtc_reader *r, ms_frame_out *fr, ms_perr *err)
{
    xtc_ahead *a = r->ahead;
    xtc_frame *f = &a->slot[a->head % a->nslots];
    int direct = 0;
    pthread_mutex_lock(&a->mu);
    while (f->state != S_DONE) {
        if (f->state == S_READ) {
            f->state = S_BUSY;
            direct = 1;
            break;
        }
        xtc_frame *later = claim_next(a);
        if (later) decode_claimed(a, later);
        else pthread_cond_wait(&a->done, &a->mu);
    }
    pthread_mutex_unlock(&a->mu);
    int rc = direct ? finish(f, a->natoms, fr, err) : deliver(f, a->natoms, fr, err);
    a->head++;
    if (rc == MS_PLUGIN_OK && fr->pos && r->kept) ahead_fill(r);
    r->kept = fr->pos != NULL;
    return rc;
}

/* ---------------------------------------------------------------- the plugin */

static int xtc_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    xtc_reader *r = h;
    if (r->ahead && r->ahead->head < r->ahead->tail) {
        if (natoms == r->ahead->natoms) return from_ahead(r, fr, err);
        return ms_perr_set(err, "the frame has %ld atoms, expected %ld", r->ahead->natoms, natoms);
    }
    xtc_frame *f = &r->sync;
    int rc = read_raw(r, f, natoms, fr->pos != NULL, err);
    if (rc == MS_PLUGIN_OK) rc = finish(f, natoms, fr, err);
    int consecutive = r->kept && fr->pos;
    r->kept = fr->pos != NULL;
    if (rc != MS_PLUGIN_OK || !consecutive || r->no_ahead) return rc;
    /* The host reads consecutive frames: read ahead from now on. */
    if (!r->ahead && !(r->ahead = ahead_start(natoms))) r->no_ahead = 1;
    if (r->ahead) ahead_fill(r);
    return MS_PLUGIN_OK;
}

/* Frames are found by their byte offset: the token is one. While frames are read ahead,
 * the next frame is the first of them, not where the file stands. */
static int xtc_tell_frame(void *h, long long *token, ms_perr *err)
{
    xtc_reader *r = h;
    xtc_ahead *a = r->ahead;
    off_t at = a && a->head < a->tail ? (off_t)a->slot[a->head % a->nslots].at : ftello(r->fp);
    if (at < 0) return ms_perr_set(err, "cannot tell the file position: %s", strerror(errno));
    *token = (long long)at;
    return MS_PLUGIN_OK;
}

/* A seek drains the reading ahead first: its threads finish the frame they decode and are
 * joined, the frames read ahead dropped; it starts again when the host next reads
 * consecutive frames. */
static int xtc_seek_frame(void *h, long long token, ms_perr *err)
{
    xtc_reader *r = h;
    if (r->ahead) ahead_stop(r->ahead);
    r->ahead = NULL;
    r->kept = 0;
    if (token < 0 || fseeko(r->fp, (off_t)token, SEEK_SET) != 0)
        return ms_perr_set(err, "cannot seek to byte %lld: %s", token, strerror(errno));
    return MS_PLUGIN_OK;
}

static void xtc_close_read(void *h)
{
    xtc_reader *r = h;
    if (r->ahead) ahead_stop(r->ahead);
    if (r->fp) fclose(r->fp);
    free(r->sync.buf);
    free(r);
}

static void *xtc_open_read(const char *path, long *natoms, ms_perr *err)
{
    xtc_reader *r = calloc(1, sizeof *r);
    unsigned char h[16];
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (!(r->fp = ms_open_sized(path, &r->size, err))) goto fail;
    if (read_exact(r->fp, h, 16) != 1) {
        ms_perr_set(err, "not an XTC file: shorter than a frame header");
        goto fail;
    }
    int32_t magic = (int32_t)ms_be32(h), n = (int32_t)ms_be32(h + 4);
    if (magic != XTC_MAGIC && magic != XTC_MAGIC_LARGE) {
        ms_perr_set(err, "not an XTC file: magic number %d, expected 1995", (int)magic);
        goto fail;
    }
    /* Every atom takes at least a few bits: refuse counts the file cannot hold. */
    if (n < 1) {
        ms_perr_set(err, "frame 0: bad atom count %d", (int)n);
        goto fail;
    }
    if ((double)n > 8.0 * (double)r->size + 16) {
        ms_perr_set(err, "frame 0: the header declares %d atoms, more than the file's %lld "
                    "bytes can hold (a few bits each, at the least)", (int)n, r->size);
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

/* ---------------------------------------------------------------- encoding */

#define XTC_PRECISION 1000.0f
#define XTC_MAXABS 2147483645.0   /* integers beyond would overflow the ranges' sizes */
#define XTC_MAX_SMALL 8           /* atoms in a run of small differences */

/* Bits written most significant first, 32 at a time; fewer than 32 wait in acc. */
typedef struct bitout {
    unsigned char *p;
    uint64_t acc;
    int n;
} bitout;

/* Append the n (<= 32) low bits of v (v < 2^n). */
static inline void put_bits(bitout *o, int n, uint64_t v)
{
    o->acc = o->acc << n | v;
    o->n += n;
    if (o->n >= 32) {
        o->n -= 32;
        uint32_t w = __builtin_bswap32((uint32_t)(o->acc >> o->n));
        memcpy(o->p, &w, 4);
        o->p += 4;
    }
}

/* The bits still waiting, the last byte padded with zeros. */
static void put_flush(bitout *o)
{
    for (; o->n >= 8; o->n -= 8) *o->p++ = (unsigned char)(o->acc >> (o->n - 8));
    if (o->n) *o->p++ = (unsigned char)(o->acc << (8 - o->n));
    o->n = 0;
}

/* The inverse of get_packed and get_ints_wide: nbits (<= 64) bits of v as bytes least
 * significant first, the last byte holding the 1..8 bits left. */
static inline void put_packed(bitout *o, int nbits, uint64_t v)
{
    int full = (nbits - 1) / 8, rest = nbits - 8 * full;
    if (full) {
        uint64_t w = __builtin_bswap64(v) >> (64 - 8 * full);
        if (full > 4) put_bits(o, 8 * full - 32, w >> 32);
        put_bits(o, full > 4 ? 32 : 8 * full, w & 0xffffffffu);
    }
    put_bits(o, rest, v >> (8 * full));
}

static void put_wide(bitout *o, int nbits, unsigned __int128 v)
{
    for (; nbits > 8; nbits -= 8, v >>= 8) put_bits(o, 8, (uint64_t)(v & 0xff));
    put_bits(o, nbits, (uint64_t)v);
}

/* The sizes of a frame's full triples (from full_sizes). */
typedef struct xtc_sizes {
    uint32_t size[3];
    int bits[3], bitsize, large;
    int32_t min[3];
} xtc_sizes;

/* An atom's integers as a full triple: separate fields for large ranges, else one number in
 * the radices size[] (the first coordinate most significant). */
static inline void put_full(bitout *o, const xtc_sizes *z, const int32_t t[3])
{
    uint32_t v[3];
    for (int d = 0; d < 3; d++) v[d] = (uint32_t)t[d] - (uint32_t)z->min[d];
    if (z->large) {
        for (int d = 0; d < 3; d++) put_bits(o, z->bits[d], v[d]);
    } else if (z->bitsize <= 64) {
        put_packed(o, z->bitsize, ((uint64_t)v[0] * z->size[1] + v[1]) * z->size[2] + v[2]);
    } else {
        unsigned __int128 x = (unsigned __int128)v[0] * z->size[1] + v[1];
        put_wide(o, z->bitsize, x * z->size[2] + v[2]);
    }
}

/* The small differences a - b (each below smallnum in size) in idx bits. */
static inline void put_small(bitout *o, int idx, int smallnum, const int32_t *a,
                             const int32_t *b)
{
    uint64_t m = (uint64_t)magicints[idx], s[3];
    for (int d = 0; d < 3; d++) s[d] = (uint64_t)((int64_t)a[d] - b[d] + smallnum);
    if (idx <= 64) put_packed(o, idx, (s[0] * m + s[1]) * m + s[2]);
    else put_wide(o, idx, ((unsigned __int128)s[0] * m + s[1]) * m + s[2]);
}

/* The largest coordinate difference of atoms a and b (below 2^32: see XTC_MAXABS). */
static inline uint32_t maxdiff(const int32_t *a, const int32_t *b)
{
    uint32_t m = 0;
    for (int d = 0; d < 3; d++) {
        int64_t x = (int64_t)a[d] - b[d];
        uint32_t u = (uint32_t)(x < 0 ? -x : x);
        m = u > m ? u : m;
    }
    return m;
}

/* Each atom's largest coordinate difference from the atom before (d1) and from the one two
 * before (d2): all that grouping atoms into runs looks at. */
static void neighbour_diffs(const int32_t *v, long natoms, uint32_t *d1, uint32_t *d2)
{
    d1[0] = d2[0] = d2[1] = UINT32_MAX;
    for (long i = 1; i < natoms; i++) {
        d1[i] = maxdiff(v + 3 * i, v + 3 * (i - 1));
        if (i > 1) d2[i] = maxdiff(v + 3 * i, v + 3 * (i - 2));
    }
}

/* The initial size index: the median of what the first (up to 31) neighbours need (the
 * smallest size whose half exceeds their difference). */
static int first_smallidx(const uint32_t *d1, long natoms)
{
    int need[31], n = 0;
    for (long i = 1; i < natoms && n < 31; i++) {
        int k = FIRSTIDX, j = n++;
        while (k < LASTIDX - 1 && (uint32_t)(magicints[k] / 2) <= d1[i]) k++;
        for (; j > 0 && need[j - 1] > k; j--) need[j] = need[j - 1];
        need[j] = k;
    }
    return n ? need[n / 2] : FIRSTIDX;
}

/* Angstrom to integers (nm times the precision, rounded half away from zero) and their
 * bounding box into h. Returns -1, or the first atom with a coordinate out of range. */
static long to_ints(const float *pos, long natoms, int32_t *v, xtc_head *h)
{
    int32_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
    const double scale = (double)XTC_PRECISION / 10.0;
    for (long i = 0; i < natoms; i++)
        for (int d = 0; d < 3; d++) {
            double x = (double)pos[3 * i + d] * scale;
            if (!(fabs(x) <= XTC_MAXABS)) return i;
            int32_t k = (int32_t)(x < 0 ? x - 0.5 : x + 0.5);
            v[3 * i + d] = k;
            lo[d] = k < lo[d] ? k : lo[d];
            hi[d] = k > hi[d] ? k : hi[d];
        }
    h->precision = XTC_PRECISION;
    memcpy(h->minint, lo, sizeof lo);
    memcpy(h->maxint, hi, sizeof hi);
    return -1;
}

#define XTC_LOOK 18   /* atoms looked ahead to choose the size */

/* The run of the group that starts at atom i, for differences below smallnum: how many
 * atoms follow the one in full. The run's first atom is i (its difference from i + 1, the
 * atom in full), then i + 2 (from i), then each from the atom before. */
static inline int run_of(const uint32_t *d1, const uint32_t *d2, long natoms, long i,
                         uint32_t smallnum)
{
    if (i + 1 >= natoms || d1[i + 1] >= smallnum) return 0;
    if (i + 2 >= natoms || d2[i + 2] >= smallnum) return 1;
    int ns = 2;
    while (ns < XTC_MAX_SMALL && i + ns + 1 < natoms && d1[i + ns + 1] < smallnum) ns++;
    return ns;
}

/* Bits the atoms from i on (XTC_LOOK of them) take at size index idx: full triples of
 * fullbits bits, a run flag and the run's length when it differs from the run before (run
 * small integers), differences of idx bits. */
static long lookahead_bits(const uint32_t *d1, const uint32_t *d2, long natoms, long i,
                           int idx, int fullbits, int run)
{
    long end = i + XTC_LOOK < natoms ? i + XTC_LOOK : natoms, bits = 0;
    uint32_t smallnum = (uint32_t)magicints[idx] / 2;
    while (i < end) {
        int ns = run_of(d1, d2, natoms, i, smallnum);
        bits += fullbits + 1 + (3 * ns != run ? 5 : 0) + (long)ns * idx;
        run = 3 * ns;
        i += ns + 1;
    }
    return bits;
}

/* The change of the size index after a group (-1, 0 or +1): the one under which the atoms
 * that follow take the fewest bits, a change costing its flag. */
static int size_change(const uint32_t *d1, const uint32_t *d2, long natoms, long next, int idx,
                       int fullbits, int run)
{
    if (next >= natoms) return 0;
    long best = lookahead_bits(d1, d2, natoms, next, idx, fullbits, run);
    int change = 0;
    for (int c = -1; c <= 1; c += 2) {
        if (idx + c < FIRSTIDX || idx + c >= LASTIDX) continue;
        long b = lookahead_bits(d1, d2, natoms, next, idx + c, fullbits, run) + 5;
        if (b < best) best = b, change = c;
    }
    return change;
}

/* Encode natoms (> 9) atoms' integers v into out (room for 13 bytes an atom and 16 more),
 * the size index chosen into h; d1 and d2 are scratch for natoms each. Returns the bytes
 * written. A group is an atom in full followed, when the atom after it is close, by a run
 * of up to XTC_MAX_SMALL atoms as small differences (run_of); the run's first atom comes
 * before the one in full in the file's order. After each group the size may step up or
 * down by one, as the atoms ahead would take fewer bits. */
static size_t encode(xtc_head *h, const int32_t *v, long natoms, uint32_t *d1, uint32_t *d2,
                     unsigned char *out)
{
    xtc_sizes z;
    ms_perr unused;
    full_sizes(h, z.size, z.bits, &z.bitsize, &z.large, &unused); /* ranges fit: to_ints */
    memcpy(z.min, h->minint, sizeof z.min);
    neighbour_diffs(v, natoms, d1, d2);
    int idx = h->smallidx = first_smallidx(d1, natoms), prevrun = -1;
    int fullbits = z.large ? z.bits[0] + z.bits[1] + z.bits[2] : z.bitsize;
    bitout o = {out, 0, 0};
    for (long i = 0; i < natoms;) {
        int smallnum = magicints[idx] / 2, ns = run_of(d1, d2, natoms, i, (uint32_t)smallnum);
        long next = i + ns + 1;
        int change = size_change(d1, d2, natoms, next, idx, fullbits, 3 * ns);
        const int32_t *a = v + 3 * i;
        put_full(&o, &z, ns ? a + 3 : a);
        if (3 * ns != prevrun || change) {
            put_bits(&o, 1, 1);
            put_bits(&o, 5, (uint64_t)(3 * ns + change + 1));
            prevrun = 3 * ns;
        } else {
            put_bits(&o, 1, 0);
        }
        if (ns) put_small(&o, idx, smallnum, a, a + 3);
        if (ns > 1) put_small(&o, idx, smallnum, a + 6, a);
        for (int k = 3; k <= ns; k++) put_small(&o, idx, smallnum, a + 3 * k, a + 3 * (k - 1));
        idx += change;
        i = next;
    }
    put_flush(&o);
    return (size_t)(o.p - out);
}

/* ---------------------------------------------------------------- writing */

typedef struct xtc_writer {
    ms_out out;
    long natoms;
    int32_t *ints;         /* the frame's integers */
    uint32_t *diffs;       /* scratch for encode: 2 natoms */
    unsigned char *buf;    /* its stream */
} xtc_writer;

static void *xtc_open_write(const char *path, long natoms, ms_perr *err)
{
    if (natoms < 1 || natoms > INT32_MAX) {
        ms_perr_set(err, "cannot write %ld atoms to an XTC file", natoms);
        return NULL;
    }
    xtc_writer *w = calloc(1, sizeof *w);
    if (w && natoms > 9) {
        w->ints = malloc((size_t)natoms * 3 * sizeof *w->ints);
        w->diffs = malloc((size_t)natoms * 2 * sizeof *w->diffs);
        w->buf = malloc((size_t)natoms * 13 + 16);
    }
    if (!w || (natoms > 9 && (!w->ints || !w->diffs || !w->buf))) {
        if (w) free(w->ints), free(w->diffs), free(w->buf);
        free(w);
        ms_perr_set(err, "out of memory for %ld atoms", natoms);
        return NULL;
    }
    if (ms_out_open(&w->out, path, err) != MS_PLUGIN_OK) {
        free(w->ints);
        free(w->diffs);
        free(w->buf);
        free(w);
        return NULL;
    }
    w->natoms = natoms;
    return w;
}

/* The frame header: magic, atoms, step, time, the box (nm; zero without a cell) and the
 * atom count again. */
static void put_header(unsigned char *b, int32_t magic, long natoms, const ms_frame_in *f)
{
    float box[9] = {0};
    if (f->cell[0] > 0 && f->cell[1] > 0 && f->cell[2] > 0) ms_gmx_cell_to_box(f->cell, box);
    ms_put_be32(b, (uint32_t)magic);
    ms_put_be32(b + 4, (uint32_t)natoms);
    ms_put_be32(b + 8, (uint32_t)f->index);
    ms_put_be_float(b + 12, (float)f->time);
    for (int k = 0; k < 9; k++) ms_put_be_float(b + 16 + 4 * k, box[k]);
    ms_put_be32(b + 52, (uint32_t)natoms);
}

/* Up to 9 atoms: the coordinates as plain floats (nm). */
static void write_plain(xtc_writer *w, const ms_frame_in *f)
{
    unsigned char b[56 + 9 * 12];
    put_header(b, XTC_MAGIC, w->natoms, f);
    for (long k = 0; k < 3 * w->natoms; k++) ms_put_be_float(b + 56 + 4 * k, f->pos[k] / 10.0f);
    ms_out_write(&w->out, b, 56 + (size_t)w->natoms * 12);
}

static int xtc_write_frame(void *hw, const ms_struct_view *view, const ms_frame_in *f,
                           ms_perr *err)
{
    (void)view;
    xtc_writer *w = hw;
    if (w->natoms <= 9) {
        write_plain(w, f);
        return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
    }
    xtc_head h;
    long bad = to_ints(f->pos, w->natoms, w->ints, &h);
    if (bad >= 0)
        return ms_perr_set(err, "frame %d: atom %ld: coordinates (%g, %g, %g) out of the XTC "
                           "range (2.1e7 A)", f->index, bad, (double)f->pos[3 * bad],
                           (double)f->pos[3 * bad + 1], (double)f->pos[3 * bad + 2]);
    size_t bytes = encode(&h, w->ints, w->natoms, w->diffs, w->diffs + w->natoms, w->buf);
    memset(w->buf + bytes, 0, 3);
    int large = bytes > INT32_MAX;   /* GROMACS' magic 2023: a 64-bit byte count */
    unsigned char b[56 + 40];
    put_header(b, large ? XTC_MAGIC_LARGE : XTC_MAGIC, w->natoms, f);
    ms_put_be_float(b + 56, h.precision);
    for (int d = 0; d < 3; d++) {
        ms_put_be32(b + 60 + 4 * d, (uint32_t)h.minint[d]);
        ms_put_be32(b + 72 + 4 * d, (uint32_t)h.maxint[d]);
    }
    ms_put_be32(b + 84, (uint32_t)h.smallidx);
    if (large) ms_put_be32(b + 88, (uint32_t)((uint64_t)bytes >> 32));
    ms_put_be32(b + 88 + 4 * large, (uint32_t)bytes);
    ms_out_write(&w->out, b, 92 + 4 * (size_t)large);
    ms_out_write(&w->out, w->buf, (bytes + 3) & ~(size_t)3);
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int xtc_close_write(void *hw, ms_perr *err)
{
    xtc_writer *w = hw;
    int rc = ms_out_close(&w->out, err);
    free(w->ints);
    free(w->diffs);
    free(w->buf);
    free(w);
    return rc;
}

static const ms_plugin xtc_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "xtc",
    .description = "GROMACS compressed trajectory",
    .extensions = "xtc",
    .caps = MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = xtc_open_read,
    .read_frame = xtc_read_frame,
    .close_read = xtc_close_read,
    .tell_frame = xtc_tell_frame,
    .seek_frame = xtc_seek_frame,
    .open_write = xtc_open_write,
    .write_frame = xtc_write_frame,
    .close_write = xtc_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &xtc_plugin; }
