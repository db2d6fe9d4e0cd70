/* imd_net.c: the client side of an IMD session's TCP connection (imd.h): connecting with a
 * time limit, the handshake and IMD_GO, sending bodiless messages, and reading what has
 * arrived without waiting (the caller reads when the event loop says the socket is ready). */
#include "config.h"
#include "imd/imd.h"

#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/types.h>
#include <unistd.h>

/* Wait until fd is ready for events within timeout seconds: 1, 0 on timeout, -1 on error. */
static int wait_fd(int fd, short events, double timeout)
{
    double end = ms_now() + timeout;
    for (;;) {
        double left = end - ms_now();
        if (left <= 0) return 0;
        struct pollfd p = {fd, events, 0};
        int r = poll(&p, 1, (int)(left * 1000) + 1);
        if (r > 0) return 1;
        if (r < 0 && errno != EINTR) return -1;
    }
}

static int set_blocking(int fd, int blocking)
{
    int fl = fcntl(fd, F_GETFL, 0);
    if (fl < 0) return -1;
    return fcntl(fd, F_SETFL, blocking ? fl & ~O_NONBLOCK : fl | O_NONBLOCK);
}

/* Connect one resolved address: the socket, or -1 with *why an errno (ETIMEDOUT for no
 * answer in time). */
static int connect_one(const struct addrinfo *ai, double timeout, int *why)
{
    int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) {
        *why = errno;
        return -1;
    }
    int r = set_blocking(fd, 0) ? -1 : connect(fd, ai->ai_addr, ai->ai_addrlen);
    if (r < 0 && errno == EINPROGRESS) {
        int w = wait_fd(fd, POLLOUT, timeout);
        int soerr = 0;
        socklen_t len = sizeof soerr;
        if (w <= 0) soerr = w == 0 ? ETIMEDOUT : errno;
        else if (getsockopt(fd, SOL_SOCKET, SO_ERROR, &soerr, &len) < 0) soerr = errno;
        r = soerr ? -1 : 0;
        errno = soerr;
    }
    if (r < 0 || set_blocking(fd, 1)) {
        *why = errno;
        close(fd);
        return -1;
    }
    int one = 1;
    struct timeval limit;        /* for sends: a peer that stops reading */
    limit.tv_sec = (time_t)timeout;
    limit.tv_usec = (suseconds_t)((timeout - (double)limit.tv_sec) * 1e6);
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
    return fd;
}

int ms_imd_connect(const char *host, int port, double timeout, ms_error *err)
{
    struct addrinfo hints, *res = NULL;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    char service[16];
    snprintf(service, sizeof service, "%d", port);
    int gai = getaddrinfo(host, service, &hints, &res);
    if (gai) {
        ms_error_set(err, "cannot resolve host '%s': %s", host, gai_strerror(gai));
        return -1;
    }
    int fd = -1, why = 0;
    for (const struct addrinfo *ai = res; ai && fd < 0; ai = ai->ai_next)
        fd = connect_one(ai, timeout, &why);
    freeaddrinfo(res);
    if (fd < 0) {
        if (why == ETIMEDOUT)
            ms_error_set(err, "cannot connect to %s port %d: no answer in %g s", host, port,
                         timeout);
        else
            ms_error_set(err, "cannot connect to %s port %d: %s", host, port, strerror(why));
    }
    return fd;
}

/* Read exactly n bytes within timeout seconds: 0, or -1 with err. */
static int recv_all(int fd, unsigned char *buf, size_t n, double timeout, ms_error *err)
{
    double end = ms_now() + timeout;
    size_t have = 0;
    while (have < n) {
        int w = wait_fd(fd, POLLIN, end - ms_now());
        if (w <= 0) {
            if (w == 0) ms_error_set(err, "no IMD handshake within %g s", timeout);
            else ms_error_set(err, "waiting for the IMD handshake: %s", strerror(errno));
            return -1;
        }
        ssize_t r = recv(fd, buf + have, n - have, 0);
        if (r == 0) {
            ms_error_set(err, "the server closed the connection %s the IMD handshake",
                         have ? "in the middle of" : "before");
            return -1;
        }
        if (r < 0 && errno != EINTR && errno != EAGAIN) {
            ms_error_set(err, "reading the IMD handshake: %s", strerror(errno));
            return -1;
        }
        if (r > 0) have += (size_t)r;
    }
    return 0;
}

int ms_imd_handshake(int fd, double timeout, int *swap, ms_error *err)
{
    unsigned char h[MS_IMD_HEADER_SIZE];
    if (recv_all(fd, h, sizeof h, timeout, err) || ms_imd_check_handshake(h, swap, err))
        return -1;
    return ms_imd_send(fd, MS_IMD_GO, 0, err);
}

int ms_imd_send(int fd, int32_t type, int32_t length, ms_error *err)
{
    unsigned char h[MS_IMD_HEADER_SIZE];
    ms_imd_encode_header(h, type, length);
    size_t sent = 0;
    while (sent < sizeof h) {
        ssize_t r = send(fd, h + sent, sizeof h - sent, MSG_NOSIGNAL);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            ms_error_set(err, "sending %s: the simulation does not read its messages",
                         ms_imd_type_name(type));
            return -1;
        }
        if (r <= 0) {
            ms_error_set(err, "sending %s: %s", ms_imd_type_name(type), strerror(errno));
            return -1;
        }
        sent += (size_t)r;
    }
    return 0;
}

long ms_imd_recv_now(int fd, unsigned char *buf, size_t size, ms_error *err)
{
    for (;;) {
        ssize_t r = recv(fd, buf, size, MSG_DONTWAIT);
        if (r > 0) return (long)r;
        if (r == 0) {
            ms_error_set(err, "the simulation closed the connection");
            return -1;
        }
        if (errno == EINTR) continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK) return 0;
        ms_error_set(err, "reading from the simulation: %s", strerror(errno));
        return -1;
    }
}
