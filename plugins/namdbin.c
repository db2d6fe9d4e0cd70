/* namdbin.c: NAMD binary coordinates and velocities (.coor, .vel): an int32 atom count and
 * three float64 per atom (x y z), in either byte order (told by the file size). One frame,
 * no structure. Velocities are stored as NAMD writes them (A per NAMD time unit). Writes
 * the host's byte order. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct nb_reader {
    FILE *fp;
    long natoms;
    int swap, done;
} nb_reader;

static uint32_t bswap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

static void nb_close_read(void *h)
{
    nb_reader *r = h;
    if (r->fp) fclose(r->fp);
    free(r);
}

static void *nb_open_read(const char *path, long *natoms, ms_perr *err)
{
    nb_reader *r = calloc(1, sizeof *r);
    uint32_t n;
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    long long size;
    if (!(r->fp = ms_open_sized(path, &size, err))) goto fail;
    if (fread(&n, 4, 1, r->fp) != 1) {
        ms_perr_set(err, "not a NAMD binary file: shorter than 4 bytes");
        goto fail;
    }
    if (n >= 1 && 4 + 24LL * n == size) r->swap = 0;
    else if (bswap32(n) >= 1 && 4 + 24LL * bswap32(n) == size) r->swap = 1, n = bswap32(n);
    else {
        ms_perr_set(err, "not a NAMD binary file: %lld bytes do not hold the %u atoms the header "
                    "gives (4 + 24 per atom)", size, n);
        goto fail;
    }
    r->natoms = *natoms = (long)n;
    return r;
fail:
    nb_close_read(r);
    return NULL;
}

static int nb_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    nb_reader *r = h;
    if (r->done) return MS_PLUGIN_EOF;
    r->done = 1;
    if (natoms != r->natoms) return ms_perr_set(err, "the file has %ld atoms, not %ld", r->natoms, natoms);
    if (!fr->pos) return MS_PLUGIN_OK;
    double buf[3 * 1024];
    for (long i = 0; i < natoms; i += 1024) {
        size_t n = (size_t)(natoms - i < 1024 ? natoms - i : 1024);
        if (fread(buf, 24, n, r->fp) != n) return ms_perr_set(err, "read error at atom %ld", i + 1);
        for (size_t k = 0; k < 3 * n; k++) {
            double d = buf[k];
            if (r->swap) {
                uint64_t u;
                memcpy(&u, &d, 8);
                u = (uint64_t)bswap32((uint32_t)u) << 32 | bswap32((uint32_t)(u >> 32));
                memcpy(&d, &u, 8);
            }
            fr->pos[3 * (size_t)i + k] = (float)d;
        }
    }
    return MS_PLUGIN_OK;
}

/* The one frame's token is 0; after it, 1 (the end). */
static int nb_tell_frame(void *h, long long *token, ms_perr *err)
{
    (void)err;
    *token = ((nb_reader *)h)->done;
    return MS_PLUGIN_OK;
}

static int nb_seek_frame(void *h, long long token, ms_perr *err)
{
    nb_reader *r = h;
    if (token != 0 && token != 1) return ms_perr_set(err, "no frame %lld", token);
    if (fseeko(r->fp, 4, SEEK_SET) != 0)
        return ms_perr_set(err, "cannot seek to the coordinates: %s", strerror(errno));
    r->done = (int)token;
    return MS_PLUGIN_OK;
}

typedef struct nb_writer {
    ms_out out;
    long natoms;
    int frames;
} nb_writer;

static void *nb_open_write(const char *path, long natoms, ms_perr *err)
{
    if (natoms < 1 || natoms > INT32_MAX) {
        ms_perr_set(err, "cannot write %ld atoms to a NAMD binary file", natoms);
        return NULL;
    }
    nb_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    w->natoms = natoms;
    return w;
}

static int nb_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    (void)v;
    nb_writer *w = h;
    if (w->frames++) return ms_perr_set(err, "a NAMD binary file holds one frame");
    int32_t n = (int32_t)w->natoms;
    ms_out_write(&w->out, &n, 4);
    for (long i = 0; i < 3 * w->natoms; i++) {
        double d = f->pos[i];
        ms_out_write(&w->out, &d, 8);
    }
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int nb_close_write(void *h, ms_perr *err)
{
    nb_writer *w = h;
    return ms_out_destroy(w, err);
}

static const ms_plugin namdbin_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "namdbin",
    .description = "NAMD binary coordinates",
    .extensions = "coor vel namdbin",
    .caps = MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = nb_open_read,
    .read_frame = nb_read_frame,
    .close_read = nb_close_read,
    .tell_frame = nb_tell_frame,
    .seek_frame = nb_seek_frame,
    .open_write = nb_open_write,
    .write_frame = nb_write_frame,
    .close_write = nb_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &namdbin_plugin; }
