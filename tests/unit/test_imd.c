/* test_imd.c: the IMD codec and connection (imd/imd.h): the header's bytes, the handshake's
 * byte-order test, bodies in both byte orders, the stream decoder fed whole and byte by byte,
 * every message it must refuse, and the connection's handshake, sends and reads over a
 * socket pair (refused connection, timeout, peer closing). */
#include "config.h"
#include "ms_test.h"
#include "imd/imd.h"

#include <netinet/in.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

static int host_little(void)
{
    const uint16_t one = 1;
    return *(const unsigned char *)&one == 1;
}

static void test_header(void)
{
    unsigned char h[8];
    const unsigned char want[8] = {0, 0, 0, 2, 0, 0, 0x01, 0x02};
    ms_imd_encode_header(h, MS_IMD_FCOORDS, 258);
    t_ok(!memcmp(h, want, 8), "header: type and length big-endian");
    int32_t type, len;
    ms_imd_encode_header(h, MS_IMD_TRATE, -5);
    ms_imd_decode_header(h, &type, &len);
    t_ok(type == MS_IMD_TRATE && len == -5, "header: round trip of a negative length");
    t_ok(!strcmp(ms_imd_type_name(MS_IMD_ENERGIES), "IMD_ENERGIES") &&
         !strcmp(ms_imd_type_name(42), "unknown"), "type names");
}

static void test_handshake_codec(void)
{
    unsigned char h[8];
    ms_error err = {{0}};
    int swap = -1;
    ms_imd_encode_handshake(h, 0);
    t_ok(ms_imd_check_handshake(h, &swap, &err) == 0 && swap == 0, "handshake: same order");
    ms_imd_encode_handshake(h, 1);
    t_ok(ms_imd_check_handshake(h, &swap, &err) == 0 && swap == 1, "handshake: swapped order");
    t_ok(h[4] == (host_little() ? 0 : 2) && h[7] == (host_little() ? 2 : 0),
         "handshake: swapped on this machine is big-endian when it is little-endian");
    ms_imd_encode_header(h, MS_IMD_FCOORDS, 2);
    t_ok(ms_imd_check_handshake(h, &swap, &err) == -1 &&
         strstr(err.msg, "got message type 2 (IMD_FCOORDS)"), "handshake: another type (%s)",
         err.msg);
    ms_imd_encode_header(h, MS_IMD_HANDSHAKE, 3);
    t_ok(ms_imd_check_handshake(h, &swap, &err) == -1 && strstr(err.msg, "version 3"),
         "handshake: version 3 refused (%s)", err.msg);
}

static void test_bodies(void)
{
    const float xyz[6] = {1.0f, -2.5f, 3.25f, 0.0f, 1e30f, -0.125f};
    unsigned char b[24];
    float back[6];
    int be_swap = host_little();    /* the swap that writes big-endian here */
    ms_imd_encode_coords(b, xyz, 2, be_swap);
    t_ok(b[0] == 0x3f && b[1] == 0x80 && b[2] == 0 && b[3] == 0, "coords: 1.0 big-endian");
    for (int swap = 0; swap < 2; swap++) {
        ms_imd_encode_coords(b, xyz, 2, swap);
        ms_imd_decode_coords(b, 2, swap, back);
        t_ok(!memcmp(back, xyz, sizeof xyz), "coords: round trip, swap %d", swap);
    }
    ms_imd_energies e = {123456, 300.5f, -1.0f, 2, 3, 4, 5, 6, 7, 8}, f;
    unsigned char eb[MS_IMD_ENERGIES_SIZE];
    ms_imd_encode_energies(eb, &e, be_swap);
    t_ok(eb[0] == 0 && eb[1] == 0x01 && eb[2] == 0xe2 && eb[3] == 0x40,
         "energies: the step first, as int32");
    ms_imd_decode_energies(eb, be_swap, &f);
    t_ok(f.tstep == 123456 && f.T == 300.5f && f.Etot == -1.0f && f.Eimpr == 8.0f,
         "energies: round trip");
}

/* A stream: a frame of 2 atoms, energies, IMD_PAUSE, IMD_DISCONNECT; its size. */
static size_t make_stream(unsigned char *s, int swap)
{
    const float xyz[6] = {1, 2, 3, 4, 5, 6};
    ms_imd_energies e = {7, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    size_t n = 0;
    ms_imd_encode_header(s + n, MS_IMD_FCOORDS, 2);
    ms_imd_encode_coords(s + (n += 8), xyz, 2, swap);
    ms_imd_encode_header(s + (n += 24), MS_IMD_ENERGIES, 1);
    ms_imd_encode_energies(s + (n += 8), &e, swap);
    ms_imd_encode_header(s + (n += MS_IMD_ENERGIES_SIZE), MS_IMD_PAUSE, 0);
    ms_imd_encode_header(s + (n += 8), MS_IMD_DISCONNECT, 0);
    return n + 8;
}

/* Feed the stream in pieces of step bytes: the types received in order, as digits. */
static void feed_all(const unsigned char *s, size_t n, size_t step, int swap, char *types,
                     float *x4)
{
    ms_imd_decoder d;
    ms_error err = {{0}};
    size_t k = 0;
    ms_imd_decoder_init(&d, 2, swap, &err);
    for (size_t at = 0; at < n;) {
        size_t piece = MS_MIN(step, n - at), used = 0;
        while (used < piece) {
            ms_imd_msg m;
            int done;
            long u = ms_imd_feed(&d, s + at + used, piece - used, &m, &done, &err);
            if (u < 0) break;
            used += (size_t)u;
            if (done) types[k++] = (char)('0' + m.type);
            if (done && m.type == MS_IMD_FCOORDS) *x4 = m.coords[3];
        }
        at += piece;
    }
    types[k] = '\0';
    ms_imd_decoder_free(&d);
}

static void test_decoder(void)
{
    unsigned char s[256];
    for (int swap = 0; swap < 2; swap++) {
        size_t n = make_stream(s, swap);
        size_t steps[] = {n, 1, 7, 13};
        for (size_t i = 0; i < MS_COUNTOF(steps); i++) {
            char types[16];
            float x4 = 0;
            feed_all(s, n, steps[i], swap, types, &x4);
            t_ok(!strcmp(types, "2170") && x4 == 4.0f,
                 "decoder: swap %d, pieces of %zu: types %s, atom 1's x %g", swap, steps[i],
                 types, x4);
        }
    }
}

/* The decoder's error on one header for 3 atoms. */
static const char *refused(int32_t type, int32_t length)
{
    static ms_error err;
    ms_imd_decoder d;
    unsigned char h[8];
    ms_imd_msg m;
    int done;
    ms_imd_decoder_init(&d, 3, 0, &err);
    ms_imd_encode_header(h, type, length);
    err.msg[0] = '\0';
    long r = ms_imd_feed(&d, h, 8, &m, &done, &err);
    ms_imd_decoder_free(&d);
    return r < 0 ? err.msg : "(accepted)";
}

static void test_refused(void)
{
    const struct { int32_t type, length; const char *want; } cases[] = {
        {MS_IMD_FCOORDS, 4, "IMD_FCOORDS for 4 atoms: the molecule has 3"},
        {MS_IMD_FCOORDS, -1, "IMD_FCOORDS for -1 atoms: the molecule has 3"},
        {MS_IMD_FCOORDS, 2147483647, "IMD_FCOORDS for 2147483647 atoms: the molecule has 3"},
        {MS_IMD_ENERGIES, 2, "IMD_ENERGIES with count 2: expected 1"},
        {MS_IMD_GO, 0, "unexpected IMD_GO from the simulation"},
        {MS_IMD_HANDSHAKE, 2, "unexpected IMD_HANDSHAKE from the simulation"},
        {MS_IMD_MDCOMM, 100000000, "unexpected IMD_MDCOMM from the simulation"},
        {MS_IMD_IOERROR, 0, "the simulation reported an I/O error (IMD_IOERROR)"},
        {-7, 0, "unknown IMD message type -7 (length 0)"},
        {99, 5, "unknown IMD message type 99 (length 5)"}};
    for (size_t i = 0; i < MS_COUNTOF(cases); i++) {
        const char *got = refused(cases[i].type, cases[i].length);
        t_ok(!strcmp(got, cases[i].want), "decoder refuses type %ld length %ld: %s",
             (long)cases[i].type, (long)cases[i].length, got);
    }
    ms_imd_decoder d;
    ms_error err = {{0}};
    t_ok(ms_imd_decoder_init(&d, (size_t)1 << 40, 0, &err) == -1 &&
         strstr(err.msg, "more than IMD can send"), "decoder: too many atoms (%s)", err.msg);
}

static void test_connection(void)
{
    int sv[2];
    ms_error err = {{0}};
    int swap = -1;
    unsigned char h[8], buf[64];
    if (socketpair(AF_UNIX, SOCK_STREAM, 0, sv)) {
        t_skip("connection", "no socketpair");
        return;
    }
    ms_imd_encode_handshake(h, 1);
    t_ok(write(sv[0], h, 8) == 8 && ms_imd_handshake(sv[1], 1.0, &swap, &err) == 0 && swap == 1,
         "handshake over a socket (%s)", err.msg);
    int32_t type = -1, len = -1;
    t_ok(read(sv[0], h, 8) == 8, "the client's answer arrives");
    ms_imd_decode_header(h, &type, &len);
    t_ok(type == MS_IMD_GO && len == 0, "the answer is IMD_GO");
    t_ok(ms_imd_recv_now(sv[1], buf, sizeof buf, &err) == 0, "recv_now: nothing yet");
    t_ok(ms_imd_send(sv[1], MS_IMD_TRATE, 9, &err) == 0 && read(sv[0], h, 8) == 8, "send");
    ms_imd_decode_header(h, &type, &len);
    t_ok(type == MS_IMD_TRATE && len == 9, "send: IMD_TRATE 9");
    t_ok(write(sv[0], "abc", 3) == 3 && ms_imd_recv_now(sv[1], buf, sizeof buf, &err) == 3,
         "recv_now: what arrived");
    double t0 = ms_now();
    t_ok(ms_imd_handshake(sv[1], 0.2, &swap, &err) == -1 &&
         !strcmp(err.msg, "no IMD handshake within 0.2 s") && ms_now() - t0 < 1.0,
         "handshake: the time limit (%s)", err.msg);
    close(sv[0]);
    t_ok(ms_imd_recv_now(sv[1], buf, sizeof buf, &err) == -1 &&
         !strcmp(err.msg, "the simulation closed the connection"), "recv_now: closed (%s)",
         err.msg);
    t_ok(ms_imd_handshake(sv[1], 1.0, &swap, &err) == -1 && strstr(err.msg, "closed the "
         "connection before"), "handshake: the peer closed (%s)", err.msg);
    close(sv[1]);
}

static void test_refused_connection(void)
{
    ms_error err = {{0}};
    int s = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a;
    socklen_t len = sizeof a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bind(s, (struct sockaddr *)&a, sizeof a);
    getsockname(s, (struct sockaddr *)&a, &len);
    close(s);                       /* a port nobody listens on */
    int port = ntohs(a.sin_port);
    t_ok(ms_imd_connect("127.0.0.1", port, 2.0, &err) == -1 &&
         strstr(err.msg, "Connection refused"), "connect: refused (%s)", err.msg);
}

int main(void)
{
    t_suite = "imd";
    test_header();
    test_handshake_codec();
    test_bodies();
    test_decoder();
    test_refused();
    test_connection();
    test_refused_connection();
    return t_done();
}
