/* imd.c: the IMD protocol's codec (imd.h): headers, the handshake's byte-order test, the
 * bodies of coordinates and energies, and the stream decoder that turns bytes arriving in
 * pieces into whole, checked messages. */
#include "config.h"
#include "imd/imd.h"

#include <stdlib.h>
#include <string.h>

static const char *const type_names[MS_IMD_NTYPES] = {
    "IMD_DISCONNECT", "IMD_ENERGIES", "IMD_FCOORDS", "IMD_GO", "IMD_HANDSHAKE",
    "IMD_KILL", "IMD_MDCOMM", "IMD_PAUSE", "IMD_TRATE", "IMD_IOERROR"};

const char *ms_imd_type_name(int32_t type)
{
    return type >= 0 && type < MS_IMD_NTYPES ? type_names[type] : "unknown";
}

/* ---------------------------------------------------------------- 32-bit words */

static void put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static uint32_t get_be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static uint32_t swap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

/* A word in the simulation's order (this machine's, byte-swapped when swap). */
static uint32_t get_word(const unsigned char *p, int swap)
{
    uint32_t v;
    memcpy(&v, p, 4);
    return swap ? swap32(v) : v;
}

static void put_word(unsigned char *p, uint32_t v, int swap)
{
    if (swap) v = swap32(v);
    memcpy(p, &v, 4);
}

static float word_float(uint32_t v)
{
    float f;
    memcpy(&f, &v, 4);
    return f;
}

static uint32_t float_word(float f)
{
    uint32_t v;
    memcpy(&v, &f, 4);
    return v;
}

/* ---------------------------------------------------------------- encoding */

void ms_imd_encode_header(unsigned char out[MS_IMD_HEADER_SIZE], int32_t type, int32_t length)
{
    put_be32(out, (uint32_t)type);
    put_be32(out + 4, (uint32_t)length);
}

void ms_imd_encode_handshake(unsigned char out[MS_IMD_HEADER_SIZE], int swap)
{
    put_be32(out, MS_IMD_HANDSHAKE);
    put_word(out + 4, MS_IMD_VERSION, swap);
}

void ms_imd_encode_coords(unsigned char *out, const float *xyz, size_t natoms, int swap)
{
    for (size_t i = 0; i < 3 * natoms; i++) put_word(out + 4 * i, float_word(xyz[i]), swap);
}

/* The nine floats of an energies body, in wire order. */
static float *energy_field(ms_imd_energies *e, int i)
{
    float *f[9] = {&e->T, &e->Etot, &e->Epot, &e->Evdw, &e->Eelec, &e->Ebond, &e->Eangle,
                   &e->Edihe, &e->Eimpr};
    return f[i];
}

void ms_imd_encode_energies(unsigned char out[MS_IMD_ENERGIES_SIZE], const ms_imd_energies *e,
                            int swap)
{
    ms_imd_energies c = *e;
    put_word(out, (uint32_t)c.tstep, swap);
    for (int i = 0; i < 9; i++) put_word(out + 4 + 4 * i, float_word(*energy_field(&c, i)), swap);
}

/* ---------------------------------------------------------------- decoding */

void ms_imd_decode_header(const unsigned char in[MS_IMD_HEADER_SIZE], int32_t *type,
                          int32_t *length)
{
    *type = (int32_t)get_be32(in);
    *length = (int32_t)get_be32(in + 4);
}

int ms_imd_check_handshake(const unsigned char in[MS_IMD_HEADER_SIZE], int *swap, ms_error *err)
{
    int32_t type = (int32_t)get_be32(in);
    uint32_t native = get_word(in + 4, 0), swapped = get_word(in + 4, 1);
    if (type != MS_IMD_HANDSHAKE) {
        ms_error_set(err, "expected the IMD handshake, got message type %ld (%s): not an "
                     "IMD server", (long)type, ms_imd_type_name(type));
        return -1;
    }
    if (native != MS_IMD_VERSION && swapped != MS_IMD_VERSION) {
        ms_error_set(err, "IMD protocol version %lu: only version %d is spoken",
                     (unsigned long)get_be32(in + 4), MS_IMD_VERSION);
        return -1;
    }
    *swap = native != MS_IMD_VERSION;
    return 0;
}

void ms_imd_decode_coords(const unsigned char *in, size_t natoms, int swap, float *xyz)
{
    if (!swap) {
        memcpy(xyz, in, 12 * natoms);
        return;
    }
    for (size_t i = 0; i < 3 * natoms; i++) xyz[i] = word_float(get_word(in + 4 * i, swap));
}

void ms_imd_decode_energies(const unsigned char in[MS_IMD_ENERGIES_SIZE], int swap,
                            ms_imd_energies *e)
{
    e->tstep = (int32_t)get_word(in, swap);
    for (int i = 0; i < 9; i++) *energy_field(e, i) = word_float(get_word(in + 4 + 4 * i, swap));
}

/* ---------------------------------------------------------------- the stream decoder */

int ms_imd_decoder_init(ms_imd_decoder *d, size_t natoms, int swap, ms_error *err)
{
    memset(d, 0, sizeof *d);
    d->natoms = natoms;
    d->swap = swap;
    size_t n = natoms ? natoms : 1;
    if (natoms > (size_t)INT32_MAX / 3) {
        ms_error_set(err, "%zu atoms: more than IMD can send", natoms);
        return -1;
    }
    d->body = malloc(MS_MAX(12 * n, (size_t)MS_IMD_ENERGIES_SIZE));
    d->coords = ms_alloc_array(n, 3 * sizeof(float));
    if (!d->body || !d->coords) {
        ms_imd_decoder_free(d);
        ms_error_set(err, "out of memory for %zu atoms", natoms);
        return -1;
    }
    return 0;
}

void ms_imd_decoder_free(ms_imd_decoder *d)
{
    free(d->body);
    free(d->coords);
    d->body = NULL;
    d->coords = NULL;
}

/* A header just completed: check it against what a client may receive and size its body.
 * 0, or -1 with err. */
static int start_message(ms_imd_decoder *d, ms_error *err)
{
    ms_imd_decode_header(d->header, &d->type, &d->length);
    const char *name = ms_imd_type_name(d->type);
    d->body_size = 0;
    switch (d->type) {
    case MS_IMD_FCOORDS:
        if (d->length < 0 || (size_t)d->length != d->natoms) {
            ms_error_set(err, "IMD_FCOORDS for %ld atoms: the molecule has %zu",
                         (long)d->length, d->natoms);
            return -1;
        }
        d->body_size = 12 * d->natoms;
        return 0;
    case MS_IMD_ENERGIES:
        if (d->length != 1) {
            ms_error_set(err, "IMD_ENERGIES with count %ld: expected 1", (long)d->length);
            return -1;
        }
        d->body_size = MS_IMD_ENERGIES_SIZE;
        return 0;
    case MS_IMD_DISCONNECT: case MS_IMD_KILL: case MS_IMD_PAUSE: case MS_IMD_TRATE:
        return 0;
    case MS_IMD_IOERROR:
        ms_error_set(err, "the simulation reported an I/O error (IMD_IOERROR)");
        return -1;
    default:
        if (d->type >= 0 && d->type < MS_IMD_NTYPES)
            ms_error_set(err, "unexpected %s from the simulation", name);
        else
            ms_error_set(err, "unknown IMD message type %ld (length %ld)", (long)d->type,
                         (long)d->length);
        return -1;
    }
}

/* The message whose body is complete, into msg. */
static void finish_message(ms_imd_decoder *d, ms_imd_msg *msg)
{
    memset(msg, 0, sizeof *msg);
    msg->type = d->type;
    msg->length = d->length;
    if (d->type == MS_IMD_FCOORDS && !d->swap) {
        msg->coords = (const float *)(const void *)d->body;   /* malloc'd: aligned */
    } else if (d->type == MS_IMD_FCOORDS) {
        ms_imd_decode_coords(d->body, d->natoms, d->swap, d->coords);
        msg->coords = d->coords;
    } else if (d->type == MS_IMD_ENERGIES) {
        ms_imd_decode_energies(d->body, d->swap, &msg->energies);
    }
    d->have = 0;
    d->in_body = 0;
}

long ms_imd_feed(ms_imd_decoder *d, const unsigned char *buf, size_t n, ms_imd_msg *msg,
                 int *done, ms_error *err)
{
    size_t used = 0;
    *done = 0;
    while (used < n || (d->in_body && d->have == d->body_size)) {
        if (!d->in_body) {
            size_t take = MS_MIN(n - used, MS_IMD_HEADER_SIZE - d->have);
            memcpy(d->header + d->have, buf + used, take);
            d->have += take;
            used += take;
            if (d->have < MS_IMD_HEADER_SIZE) break;
            if (start_message(d, err)) return -1;
            d->in_body = 1;
            d->have = 0;
        }
        size_t take = MS_MIN(n - used, d->body_size - d->have);
        memcpy(d->body + d->have, buf + used, take);
        d->have += take;
        used += take;
        if (d->have == d->body_size) {
            finish_message(d, msg);
            *done = 1;
            break;
        }
    }
    return (long)used;
}
