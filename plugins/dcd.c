/* dcd.c: the DCD trajectory plugin (CHARMM, NAMD and X-PLOR). Reads either byte order,
 * 32- and 64-bit Fortran record markers, the CHARMM unit-cell record (angles as degrees or
 * as cosines), fixed atoms (later frames hold only the free ones) and CHARMM 4D files (the
 * fourth dimension is skipped). A frame is one pread() and one pass that interleaves x, y
 * and z. Writes CHARMM-style files with the unit cell, as NAMD does. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define DCD_PI 3.14159265358979323846
#define DCD_MAX_UNCHECKED_ATOMS (1L << 24)
#define DCD_HOST_BYTES 64.0   /* memory per atom of a molecule */

typedef struct dcd_reader {
    int fd;
    int swap;              /* the file's byte order is not ours */
    int mk;                /* record marker size: 4 or 8 */
    int has_cell, four_d;
    long natoms, nfree;    /* nfree < natoms when atoms are fixed */
    uint32_t *free_idx;    /* 0-based indices of the free atoms */
    float *first;          /* the first frame: later frames take fixed atoms from it */
    long long data_start;  /* offset of the first frame */
    long long first_bytes, frame_bytes, size;
    long nframes;          /* complete frames in the file */
    long long partial;     /* bytes of an incomplete frame after the last one */
    long next;             /* the frame read_frame returns next */
    unsigned char *buf;
    size_t buf_cap;
} dcd_reader;

/* ---------------------------------------------------------------- bytes */

static uint32_t bswap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

static uint64_t bswap64(uint64_t v)
{
    return ((uint64_t)bswap32((uint32_t)v) << 32) | bswap32((uint32_t)(v >> 32));
}

static uint32_t get32(const unsigned char *p, int swap)
{
    uint32_t v;
    memcpy(&v, p, 4);
    return swap ? bswap32(v) : v;
}

static uint64_t get64(const unsigned char *p, int swap)
{
    uint64_t v;
    memcpy(&v, p, 8);
    return swap ? bswap64(v) : v;
}

static double get_double(const unsigned char *p, int swap)
{
    uint64_t v = get64(p, swap);
    double d;
    memcpy(&d, &v, 8);
    return d;
}

/* A record marker of the file's width. */
static uint64_t get_marker(const dcd_reader *r, const unsigned char *p)
{
    return r->mk == 8 ? get64(p, r->swap) : get32(p, r->swap);
}

/* Read exactly n bytes at offset off; returns the bytes read (n unless the file ends). */
static size_t pread_full(int fd, void *buf, size_t n, long long off)
{
    size_t got = 0;
    while (got < n) {
        ssize_t k = pread(fd, (char *)buf + got, n - got, (off_t)(off + (long long)got));
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        got += (size_t)k;
    }
    return got;
}

/* ---------------------------------------------------------------- header */

/* Byte order and marker width from the first record, whose length is 84. */
static int detect_layout(dcd_reader *r, ms_perr *err)
{
    unsigned char b[8];
    if (pread_full(r->fd, b, 8, 0) != 8) return ms_perr_set(err, "not a DCD file: too short");
    /* 64-bit first: a little-endian 64-bit 84 also reads as a 32-bit 84. */
    for (int mk = 8; mk >= 4; mk -= 4)
        for (int swap = 0; swap < 2; swap++)
            if ((mk == 8 ? get64(b, swap) : get32(b, swap)) == 84) {
                r->swap = swap;
                r->mk = mk;
                return MS_PLUGIN_OK;
            }
    return ms_perr_set(err, "not a DCD file: the first record is not 84 bytes long");
}

/* Read a record's leading marker at *off, check it against want (any when want < 0), and
 * return its length; *off moves past the marker. */
static long long record_start(dcd_reader *r, long long *off, long long want, const char *what,
                              ms_perr *err)
{
    unsigned char b[8];
    if (pread_full(r->fd, b, (size_t)r->mk, *off) != (size_t)r->mk)
        return ms_perr_set(err, "header: the file ends before the %s record", what);
    uint64_t len = get_marker(r, b);
    if (len > (uint64_t)r->size || (want >= 0 && len != (uint64_t)want))
        return ms_perr_set(err, "header: bad %s record length %llu", what,
                           (unsigned long long)len);
    *off += r->mk;
    return (long long)len;
}

/* Check the trailing marker of a record of length len ending at *off + len. */
static int record_end(dcd_reader *r, long long *off, long long len, const char *what,
                      ms_perr *err)
{
    unsigned char b[8];
    *off += len;
    if (pread_full(r->fd, b, (size_t)r->mk, *off) != (size_t)r->mk)
        return ms_perr_set(err, "header: the file ends inside the %s record", what);
    if (get_marker(r, b) != (uint64_t)len)
        return ms_perr_set(err, "header: the %s record's end marker does not match its start",
                           what);
    *off += r->mk;
    return MS_PLUGIN_OK;
}

/* The 84-byte control record: signature and 20 integers. */
static int read_control(dcd_reader *r, long long *off, int32_t icntrl[20], ms_perr *err)
{
    unsigned char b[84];
    if (record_start(r, off, 84, "control", err) < 0) return MS_PLUGIN_ERROR;
    if (pread_full(r->fd, b, 84, *off) != 84)
        return ms_perr_set(err, "header: the file ends inside the control record");
    if (memcmp(b, "CORD", 4) != 0 && memcmp(b, "VELD", 4) != 0)
        return ms_perr_set(err, "not a DCD file: no CORD signature");
    for (int k = 0; k < 20; k++) icntrl[k] = (int32_t)get32(b + 4 + 4 * k, r->swap);
    return record_end(r, off, 84, "control", err);
}

/* Atom count and, with fixed atoms, the list of free ones. */
static int read_atoms(dcd_reader *r, long long *off, long nfixed, ms_perr *err)
{
    unsigned char b[4];
    if (record_start(r, off, 4, "atom count", err) < 0) return MS_PLUGIN_ERROR;
    if (pread_full(r->fd, b, 4, *off) != 4)
        return ms_perr_set(err, "header: the file ends inside the atom count record");
    int32_t n = (int32_t)get32(b, r->swap);
    if (n <= 0) return ms_perr_set(err, "header: bad atom count %d", (int)n);
    if (record_end(r, off, 4, "atom count", err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    r->natoms = n;
    if (nfixed < 0 || nfixed >= n)
        return ms_perr_set(err, "header: %ld fixed atoms of %ld", nfixed, r->natoms);
    r->nfree = n - nfixed;
    if (nfixed == 0) return MS_PLUGIN_OK;
    long long len = 4LL * r->nfree;
    if (record_start(r, off, len, "free atom list", err) < 0) return MS_PLUGIN_ERROR;
    r->free_idx = malloc((size_t)len);
    if (!r->free_idx) return ms_perr_set(err, "out of memory");
    if (pread_full(r->fd, r->free_idx, (size_t)len, *off) != (size_t)len)
        return ms_perr_set(err, "header: the file ends inside the free atom list");
    for (long k = 0; k < r->nfree; k++) {
        uint32_t v = get32((unsigned char *)&r->free_idx[k], r->swap);
        if (v < 1 || v > (uint32_t)n)
            return ms_perr_set(err, "header: free atom %ld is atom %u, outside 1..%ld", k + 1, v,
                               r->natoms);
        r->free_idx[k] = v - 1;
    }
    return record_end(r, off, len, "free atom list", err);
}

static long long frame_size(const dcd_reader *r, long n)
{
    long long rec = 2LL * r->mk + 4LL * n;
    return (r->has_cell ? 2LL * r->mk + 48 : 0) + (r->four_d ? 4 : 3) * rec;
}

/* A file with no frame cannot bound its atom count: refuse one that would make a huge empty
 * molecule out of a few hundred bytes (a structure file never needs it): more than
 * DCD_MAX_UNCHECKED_ATOMS, or more than memory holds (the host keeps about DCD_HOST_BYTES
 * per atom). */
static int check_unvouched(const dcd_reader *r, ms_perr *err)
{
    if (r->natoms > DCD_MAX_UNCHECKED_ATOMS)
        return ms_perr_set(err, "header: declares %ld atoms, but the file holds no frame to "
                           "vouch for them (at most %ld are taken on trust)", r->natoms,
                           DCD_MAX_UNCHECKED_ATOMS);
    long long avail = ms_plugin_mem_available();
    double need = (double)r->natoms * DCD_HOST_BYTES;
    if (avail < 0 || need <= (double)avail) return MS_PLUGIN_OK;
    return ms_perr_set(err, "header: declares %ld atoms, but the file holds no frame to vouch "
                       "for them, and they would need about %.0f MB, more than the %.0f MB of "
                       "memory available", r->natoms, need / 1048576, (double)avail / 1048576);
}

/* Count the frames the file holds; an incomplete first frame is an error now, a later one
 * when it is reached. */
static int count_frames(dcd_reader *r, ms_perr *err)
{
    r->first_bytes = frame_size(r, r->natoms);
    r->frame_bytes = frame_size(r, r->nfree);
    long long rest = r->size - r->data_start;
    if (rest <= 0) return check_unvouched(r, err);
    if (rest < r->first_bytes)
        return ms_perr_set(err, "frame 0: truncated: the file ends %lld bytes into it (a frame "
                           "of %ld atoms is %lld bytes)", rest, r->natoms, r->first_bytes);
    rest -= r->first_bytes;
    r->nframes = 1 + (long)(rest / r->frame_bytes);
    r->partial = rest % r->frame_bytes;
    return MS_PLUGIN_OK;
}

static void dcd_close_read(void *h)
{
    dcd_reader *r = h;
    if (r->fd >= 0) close(r->fd);
    free(r->free_idx);
    free(r->first);
    free(r->buf);
    free(r);
}

static void *dcd_open_read(const char *path, long *natoms, ms_perr *err)
{
    dcd_reader *r = calloc(1, sizeof *r);
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    r->fd = open(path, O_RDONLY);
    struct stat sb;
    if (r->fd < 0 || fstat(r->fd, &sb) != 0) {
        ms_perr_set(err, "%s", strerror(errno));
        goto fail;
    }
    r->size = (long long)sb.st_size;
#ifdef POSIX_FADV_SEQUENTIAL
    posix_fadvise(r->fd, 0, 0, POSIX_FADV_SEQUENTIAL);
#endif
    int32_t icntrl[20];
    long long off = 0, len;
    if (detect_layout(r, err) || read_control(r, &off, icntrl, err)) goto fail;
    /* CHARMM files carry a version number in the last field; X-PLOR files have none and
     * keep a double time step where CHARMM keeps the cell and 4D flags. */
    int charmm = icntrl[19] != 0;
    r->has_cell = charmm && icntrl[10] != 0;
    r->four_d = charmm && icntrl[11] != 0;
    if ((len = record_start(r, &off, -1, "title", err)) < 0 ||
        record_end(r, &off, len, "title", err) || read_atoms(r, &off, icntrl[8], err))
        goto fail;
    r->data_start = off;
    if (count_frames(r, err)) goto fail;
    *natoms = r->natoms;
    return r;
fail:
    dcd_close_read(r);
    return NULL;
}

/* ---------------------------------------------------------------- frames */

static float to_float(double v)
{
    if (v > FLT_MAX) return INFINITY;
    if (v < -FLT_MAX) return -INFINITY;
    return (float)v;
}

/* The CHARMM cell record is A, gamma, B, beta, alpha, C. Angles within [-1, 1] are cosines
 * (CHARMM, NAMD >= 2.5), else degrees; 90 - asin() keeps right angles exact. */
static void cell_from_record(const unsigned char *p, int swap, float cell[6])
{
    double u[6];
    for (int k = 0; k < 6; k++) u[k] = get_double(p + 8 * k, swap);
    double ang[3] = {u[4], u[3], u[1]};
    int cosines = fabs(ang[0]) <= 1.0 && fabs(ang[1]) <= 1.0 && fabs(ang[2]) <= 1.0;
    if (cosines)
        for (int k = 0; k < 3; k++) ang[k] = 90.0 - asin(ang[k]) * 180.0 / DCD_PI;
    cell[0] = to_float(u[0]);
    cell[1] = to_float(u[2]);
    cell[2] = to_float(u[5]);
    for (int k = 0; k < 3; k++) cell[3 + k] = to_float(ang[k]);
}

/* Interleave n values of x, y, z records into xyz triples. */
static void interleave(float *dst, const unsigned char *x, const unsigned char *y,
                       const unsigned char *z, size_t n, int swap)
{
    if (!swap) {
        for (size_t i = 0; i < n; i++) {
            memcpy(dst + 3 * i, x + 4 * i, 4);
            memcpy(dst + 3 * i + 1, y + 4 * i, 4);
            memcpy(dst + 3 * i + 2, z + 4 * i, 4);
        }
        return;
    }
    for (size_t i = 0; i < n; i++) {
        uint32_t v[3] = {get32(x + 4 * i, 1), get32(y + 4 * i, 1), get32(z + 4 * i, 1)};
        memcpy(dst + 3 * i, v, 12);
    }
}

/* Free atoms of a later frame: take the first frame, then place the free ones. */
static void scatter(const dcd_reader *r, float *dst, const unsigned char *x,
                    const unsigned char *y, const unsigned char *z)
{
    memcpy(dst, r->first, (size_t)r->natoms * 3 * sizeof(float));
    for (long j = 0; j < r->nfree; j++) {
        float *p = dst + 3 * (size_t)r->free_idx[j];
        uint32_t v[3] = {get32(x + 4 * j, r->swap), get32(y + 4 * j, r->swap),
                         get32(z + 4 * j, r->swap)};
        memcpy(p, v, 12);
    }
}

/* Check the markers of one frame in buf; point xyz[0..2] at the coordinate data. */
static int check_frame(const dcd_reader *r, const unsigned char *buf, long n,
                       const unsigned char *xyz[3], ms_perr *err)
{
    static const char *const what[4] = {"x", "y", "z", "4th dimension"};
    const unsigned char *p = buf;
    uint64_t len = (uint64_t)4 * (uint64_t)n;
    if (r->has_cell) {
        if (get_marker(r, p) != 48 || get_marker(r, p + r->mk + 48) != 48)
            return ms_perr_set(err, "bad unit cell record marker");
        p += 2 * r->mk + 48;
    }
    for (int d = 0; d < (r->four_d ? 4 : 3); d++) {
        uint64_t a = get_marker(r, p), b = get_marker(r, p + r->mk + len);
        if (a != len || b != len)
            return ms_perr_set(err, "bad %s record marker (%llu, expected %llu)", what[d],
                               (unsigned long long)(a != len ? a : b),
                               (unsigned long long)len);
        if (d < 3) xyz[d] = p + r->mk;
        p += 2 * r->mk + len;
    }
    return MS_PLUGIN_OK;
}

static int dcd_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    dcd_reader *r = h;
    long k = r->next;
    if (k >= r->nframes) {
        if (r->partial && k == r->nframes)
            return ms_perr_set(err, "truncated: the file ends %lld bytes into this frame (a frame "
                               "is %lld bytes)", r->partial, r->frame_bytes);
        return MS_PLUGIN_EOF;
    }
    if (natoms != r->natoms)
        return ms_perr_set(err, "the file has %ld atoms, not %ld", r->natoms, natoms);
    int keeps_first = k == 0 && r->nfree < r->natoms;
    r->next++;
    if (!fr->pos && !keeps_first) return MS_PLUGIN_OK;
    long long off = r->data_start + (k ? r->first_bytes + (k - 1) * r->frame_bytes : 0);
    size_t bytes = (size_t)(k ? r->frame_bytes : r->first_bytes);
    if (bytes > r->buf_cap) {
        unsigned char *nb = realloc(r->buf, bytes);
        if (!nb) return ms_perr_set(err, "out of memory for a frame of %zu bytes", bytes);
        r->buf = nb;
        r->buf_cap = bytes;
    }
    errno = 0;
    if (pread_full(r->fd, r->buf, bytes, off) != bytes) {
        if (errno) return ms_perr_set(err, "read error: %s", strerror(errno));
        return ms_perr_set(err, "the file ends before this frame: it is shorter than when it "
                           "was opened");
    }
    long n = k ? r->nfree : r->natoms;
    const unsigned char *xyz[3];
    if (check_frame(r, r->buf, n, xyz, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    if (r->has_cell) {
        cell_from_record(r->buf + r->mk, r->swap, fr->cell);
        fr->has_cell = 1;
    }
    if (keeps_first) {
        if (!r->first && !(r->first = malloc((size_t)r->natoms * 3 * sizeof(float))))
            return ms_perr_set(err, "out of memory");
        interleave(r->first, xyz[0], xyz[1], xyz[2], (size_t)n, r->swap);
        if (fr->pos) memcpy(fr->pos, r->first, (size_t)n * 3 * sizeof(float));
    } else if (n == r->natoms) {
        interleave(fr->pos, xyz[0], xyz[1], xyz[2], (size_t)n, r->swap);
    } else if (!r->first) {
        return ms_perr_set(err, "the first frame, which holds the fixed atoms, was not read");
    } else {
        scatter(r, fr->pos, xyz[0], xyz[1], xyz[2]);
    }
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct dcd_writer {
    ms_out out;
    long natoms;
    int32_t nframes;
    float *comp;       /* one coordinate of every atom */
} dcd_writer;

static void put32(ms_out *o, int32_t v) { ms_out_write(o, &v, 4); }

/* A record: leading marker, data, trailing marker. */
static void put_record(ms_out *o, const void *data, size_t n)
{
    put32(o, (int32_t)n);
    ms_out_write(o, data, n);
    put32(o, (int32_t)n);
}

/* CHARMM's control record as NAMD writes it: version 24, a unit cell in every frame. */
static void write_header(ms_out *o, long natoms)
{
    unsigned char ctl[84];
    int32_t icntrl[20] = {0};
    float delta = 1.0f / 0.0488882129f; /* one picosecond in AKMA time units */
    icntrl[2] = 1;                      /* NSAVC */
    memcpy(&icntrl[9], &delta, 4);
    icntrl[10] = 1;                     /* unit cell present */
    icntrl[19] = 24;                    /* CHARMM version */
    memcpy(ctl, "CORD", 4);
    memcpy(ctl + 4, icntrl, sizeof icntrl);
    put_record(o, ctl, 84);
    char title[4 + 160 + 1]; /* + 1 for snprintf's NUL, not written */
    int32_t ntitle = 2;
    memcpy(title, &ntitle, 4);
    snprintf(title + 4, 81, "%-80s", "REMARKS written by molscope");
    snprintf(title + 84, 81, "%-80s", "REMARKS CHARMM-style DCD with unit cell (A, cos g, B, cos b, cos a, C)");
    put_record(o, title, 4 + 160);
    int32_t n = (int32_t)natoms;
    put_record(o, &n, 4);
}

static void *dcd_open_write(const char *path, long natoms, ms_perr *err)
{
    if (natoms < 1 || natoms > INT32_MAX / 4) {
        ms_perr_set(err, "cannot write %ld atoms to a DCD file", natoms);
        return NULL;
    }
    dcd_writer *w = calloc(1, sizeof *w);
    if (!w || !(w->comp = malloc((size_t)natoms * sizeof(float)))) {
        if (w) free(w);
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (ms_out_open(&w->out, path, err) != MS_PLUGIN_OK) {
        free(w->comp);
        free(w);
        return NULL;
    }
    w->natoms = natoms;
    write_header(&w->out, natoms);
    return w;
}

static double cos_deg(float deg)
{
    if (deg == 90.0f) return 0.0; /* exact, so right angles read back exactly */
    return cos((double)deg * DCD_PI / 180.0);
}

static int dcd_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    dcd_writer *w = h;
    ms_out *o = &w->out;
    double cell[6] = {f->cell[0], cos_deg(f->cell[5]), f->cell[1],
                      cos_deg(f->cell[4]), cos_deg(f->cell[3]), f->cell[2]};
    put_record(o, cell, sizeof cell);
    size_t n = (size_t)w->natoms;
    for (int d = 0; d < 3; d++) {
        for (size_t i = 0; i < n; i++) w->comp[i] = f->pos[3 * i + (size_t)d];
        put_record(o, w->comp, n * sizeof(float));
    }
    w->nframes++;
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

/* Put the frame count into the header (NSET and NSTEP), then close. */
static int dcd_close_write(void *h, ms_perr *err)
{
    dcd_writer *w = h;
    ms_out *o = &w->out;
    if (!o->failed) {
        int32_t nset = w->nframes;
        if (fseeko(o->fp, 8, SEEK_SET) != 0) o->failed = errno ? errno : EIO;
        put32(o, nset);
        if (!o->failed && fseeko(o->fp, 20, SEEK_SET) != 0) o->failed = errno ? errno : EIO;
        put32(o, nset);
    }
    int rc = ms_out_close(o, err);
    free(w->comp);
    free(w);
    return rc;
}

/* Frames are found by number: the token is one. */
static int dcd_tell_frame(void *h, long long *token, ms_perr *err)
{
    (void)err;
    *token = ((dcd_reader *)h)->next;
    return MS_PLUGIN_OK;
}

static int dcd_seek_frame(void *h, long long token, ms_perr *err)
{
    dcd_reader *r = h;
    if (token < 0 || token > r->nframes) return ms_perr_set(err, "no frame %lld", token);
    r->next = (long)token;
    return MS_PLUGIN_OK;
}

static const ms_plugin dcd_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "dcd",
    .description = "CHARMM, NAMD and X-PLOR binary trajectory",
    .extensions = "dcd",
    .caps = MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = dcd_open_read,
    .read_frame = dcd_read_frame,
    .close_read = dcd_close_read,
    .open_write = dcd_open_write,
    .write_frame = dcd_write_frame,
    .close_write = dcd_close_write,
    .tell_frame = dcd_tell_frame,
    .seek_frame = dcd_seek_frame,
};

const ms_plugin *ms_plugin_entry(void) { return &dcd_plugin; }
