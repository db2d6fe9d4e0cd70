/* guard.c: the live server's connection guard (guard.h): untrusted connections listed by
 * age, closed when too old or too many. Closing is a shutdown() of the socket, which
 * libmicrohttpd then sees as the client's end of the connection and cleans up as usual. */
#include "config.h"
#include "live/guard.h"
#include "base/base.h"

#include <stdlib.h>
#include <sys/socket.h>

struct ms_live_conn {
    int fd;
    double opened;              /* ms_now() at the accept */
    int listed;                 /* in the untrusted list (not trusted, not dropped) */
    ms_live_conn *prev, *next;
};

static void unlist(ms_live_guard *g, ms_live_conn *k)
{
    if (!k->listed) return;
    if (k->prev) k->prev->next = k->next;
    else g->oldest = k->next;
    if (k->next) k->next->prev = k->prev;
    else g->newest = k->prev;
    k->prev = k->next = NULL;
    k->listed = 0;
    g->untrusted--;
}

static void drop(ms_live_guard *g, ms_live_conn *k)
{
    unlist(g, k);
    if (k->fd >= 0) shutdown(k->fd, SHUT_RDWR);
    g->dropped++;
}

/* Whether bytes wait unread on k's socket: a request the server has not parsed yet, perhaps
 * the one with the token, so that an eviction passes it over for an idle connection. */
static int unread(const ms_live_conn *k)
{
    char b;
    return k->fd >= 0 && recv(k->fd, &b, 1, MSG_PEEK | MSG_DONTWAIT) > 0;
}

/* The untrusted connection to close when too many are open: the oldest with nothing unread
 * (a flood's connections send nothing), else the oldest. */
static ms_live_conn *victim(const ms_live_guard *g)
{
    for (ms_live_conn *k = g->oldest; k; k = k->next)
        if (!unread(k)) return k;
    return g->oldest;
}

static void opened(ms_live_guard *g, struct MHD_Connection *c, void **socket_context)
{
    ms_live_conn *k = calloc(1, sizeof *k);
    if (!k) return;     /* untracked: libmicrohttpd's own time-out still closes it */
    const union MHD_ConnectionInfo *fi =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
    k->fd = fi ? fi->connect_fd : -1;
    k->opened = ms_now();
    k->listed = 1;
    k->prev = g->newest;
    if (g->newest) g->newest->next = k;
    else g->oldest = k;
    g->newest = k;
    g->untrusted++;
    *socket_context = k;
    while (g->untrusted > MS_LIVE_MAX_UNTRUSTED) drop(g, victim(g));
}

void ms_live_guard_notify(void *cls, struct MHD_Connection *c, void **socket_context,
                          enum MHD_ConnectionNotificationCode code)
{
    ms_live_guard *g = cls;
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        opened(g, c, socket_context);
    } else if (code == MHD_CONNECTION_NOTIFY_CLOSED && *socket_context) {
        unlist(g, *socket_context);
        free(*socket_context);
        *socket_context = NULL;
    }
}

void ms_live_guard_trust(ms_live_guard *g, struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *si =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    ms_live_conn *k = si ? si->socket_context : NULL;
    if (!k || !k->listed) return;
    unlist(g, k);
    MHD_set_connection_option(c, MHD_CONNECTION_OPTION_TIMEOUT, (unsigned)MS_LIVE_TRUSTED_IDLE_S);
}

long ms_live_guard_expire(ms_live_guard *g)
{
    double now = ms_now();
    while (g->oldest && now - g->oldest->opened >= MS_LIVE_UNTRUSTED_S) drop(g, g->oldest);
    if (!g->oldest) return -1;
    return (long)((g->oldest->opened + MS_LIVE_UNTRUSTED_S - now) * 1000.0) + 1;
}
