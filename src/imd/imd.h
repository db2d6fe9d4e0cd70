/* imd.h: the Interactive Molecular Dynamics (IMD) wire protocol, version 2, as NAMD,
 * GROMACS and LAMMPS speak it, and the client side of its TCP connection.
 *
 * Every message starts with an 8-byte header: the type and a length, each a 32-bit integer
 * in network (big-endian) order. What "length" means depends on the type: the number of
 * atoms of IMD_FCOORDS (a body of 3 * length 32-bit floats, x y z per atom), 1 for
 * IMD_ENERGIES (a 40-byte body: the step as int32 and nine floats), the rate of IMD_TRATE,
 * the protocol version of IMD_HANDSHAKE, 0 for the rest, which have no body.
 *
 * The handshake is the one message whose length is NOT in network order: the simulation
 * writes the version (2) in its own byte order, and the client learns from it whether the
 * bodies (floats and integers, always in the simulation's order) must be byte-swapped.
 * The client then answers IMD_GO and coordinates and energies flow.
 *
 * The decoder (ms_imd_decoder) takes bytes as they arrive, in pieces of any size, and hands
 * back whole messages; a message that cannot be right (unknown type, a coordinate count
 * other than the molecule's, a negative or huge length) is an error before anything is
 * allocated for it. Nothing here knows about Tcl or molecules. */
#ifndef MS_IMD_H
#define MS_IMD_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"

/* message types (IMDType) */
enum {
    MS_IMD_DISCONNECT = 0, MS_IMD_ENERGIES = 1, MS_IMD_FCOORDS = 2, MS_IMD_GO = 3,
    MS_IMD_HANDSHAKE = 4, MS_IMD_KILL = 5, MS_IMD_MDCOMM = 6, MS_IMD_PAUSE = 7,
    MS_IMD_TRATE = 8, MS_IMD_IOERROR = 9, MS_IMD_NTYPES = 10
};

#define MS_IMD_VERSION 2
#define MS_IMD_HEADER_SIZE 8
#define MS_IMD_ENERGIES_SIZE 40

/* The name of a message type ("IMD_FCOORDS"), or "unknown". */
const char *ms_imd_type_name(int32_t type);

/* IMD_ENERGIES' body. */
typedef struct ms_imd_energies {
    int32_t tstep;
    float T, Etot, Epot, Evdw, Eelec, Ebond, Eangle, Edihe, Eimpr;
} ms_imd_energies;

/* ---------------------------------------------------------------- encoding */

/* A header: type and length in network order. */
void ms_imd_encode_header(unsigned char out[MS_IMD_HEADER_SIZE], int32_t type, int32_t length);
/* The simulation's side of the handshake (for tests and servers): IMD_HANDSHAKE in network
 * order, then the version in the byte order swap says (0: this machine's). */
void ms_imd_encode_handshake(unsigned char out[MS_IMD_HEADER_SIZE], int swap);
/* Bodies as a simulation with byte order swap (0: this machine's) writes them: 12 * natoms
 * bytes, and MS_IMD_ENERGIES_SIZE bytes. */
void ms_imd_encode_coords(unsigned char *out, const float *xyz, size_t natoms, int swap);
void ms_imd_encode_energies(unsigned char out[MS_IMD_ENERGIES_SIZE], const ms_imd_energies *e,
                            int swap);

/* ---------------------------------------------------------------- decoding */

/* A header's type and length (network order). */
void ms_imd_decode_header(const unsigned char in[MS_IMD_HEADER_SIZE], int32_t *type,
                          int32_t *length);
/* Check a handshake header: 0 and *swap (1: the simulation's byte order is not this
 * machine's), or -1 with err saying what came instead (another type, another version). */
int ms_imd_check_handshake(const unsigned char in[MS_IMD_HEADER_SIZE], int *swap, ms_error *err);
/* Bodies in the simulation's byte order (swap) to this machine's. */
void ms_imd_decode_coords(const unsigned char *in, size_t natoms, int swap, float *xyz);
void ms_imd_decode_energies(const unsigned char in[MS_IMD_ENERGIES_SIZE], int swap,
                            ms_imd_energies *e);

/* One whole message from the simulation. */
typedef struct ms_imd_msg {
    int32_t type, length;
    const float *coords;         /* IMD_FCOORDS: 3 * natoms floats (valid until the next feed) */
    ms_imd_energies energies;    /* IMD_ENERGIES */
} ms_imd_msg;

/* The stream decoder of a session after the handshake. */
typedef struct ms_imd_decoder {
    size_t natoms;               /* the coordinate count IMD_FCOORDS must have */
    int swap;
    unsigned char header[MS_IMD_HEADER_SIZE];
    size_t have;                 /* bytes of the header, then of the body, received */
    int in_body;
    int32_t type, length;
    size_t body_size;
    unsigned char *body;         /* 12 * natoms bytes at most */
    float *coords;
} ms_imd_decoder;

/* Set up a decoder for natoms atoms and the handshake's swap (-1: out of memory). */
int ms_imd_decoder_init(ms_imd_decoder *d, size_t natoms, int swap, ms_error *err);
void ms_imd_decoder_free(ms_imd_decoder *d);
/* Take bytes from buf[0..n): the count used (it stops after one whole message, *done set to
 * 1 and *msg filled; else *done is 0 and all n were used), or -1 with err naming the
 * problem (the stream cannot go on). Messages a client never receives (IMD_GO,
 * IMD_HANDSHAKE, IMD_MDCOMM) and IMD_IOERROR are errors. */
long ms_imd_feed(ms_imd_decoder *d, const unsigned char *buf, size_t n, ms_imd_msg *msg,
                 int *done, ms_error *err);

/* ---------------------------------------------------------------- the connection */

/* A TCP connection to host:port within timeout seconds: the socket, or -1 with err (the
 * host unknown, the connection refused, no answer in time). Sends on it give up after the
 * same time when the peer stops reading. */
int ms_imd_connect(const char *host, int port, double timeout, ms_error *err);
/* Wait up to timeout seconds for the simulation's handshake, check it and answer IMD_GO:
 * 0 and *swap, or -1 with err (nothing in time, the peer closed, not an IMD handshake). */
int ms_imd_handshake(int fd, double timeout, int *swap, ms_error *err);
/* Send a message without a body: 0, or -1 with err. */
int ms_imd_send(int fd, int32_t type, int32_t length, ms_error *err);
/* Read what the socket has now, without waiting, into buf: the count (0: nothing yet), or
 * -1 with err (the peer closed the connection: "closed"; a socket error). */
long ms_imd_recv_now(int fd, unsigned char *buf, size_t size, ms_error *err);

#endif
