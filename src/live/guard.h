/* guard.h: the live server's defence against connections that never show the token
 * (doc/SECURITY.md). Any local user can connect to 127.0.0.1, and on the loopback every
 * client has the same address, so a limit per address would lock the page out too. The
 * guard instead follows each connection from its accept: one that has not yet sent a
 * request with the token is untrusted, may stay open MS_LIVE_UNTRUSTED_S seconds at most
 * (however slowly it sends), and when more than MS_LIVE_MAX_UNTRUSTED are open the oldest
 * with no bytes waiting unread is closed at each new accept (a request not yet parsed may be
 * the page's own; when every one has bytes waiting, the oldest). A connection whose request showed the token is trusted from
 * then on: the guard leaves it alone and it gets the longer idle time-out. Private to the
 * server (it includes libmicrohttpd's header). */
#ifndef MS_LIVE_GUARD_H
#define MS_LIVE_GUARD_H

#include <microhttpd.h>

#define MS_LIVE_MAX_CONNECTIONS 256  /* all connections (libmicrohttpd's limit) */
#define MS_LIVE_MAX_UNTRUSTED 32     /* open connections that have not shown the token */
#define MS_LIVE_UNTRUSTED_S 5        /* the longest one of them stays open */
#define MS_LIVE_TRUSTED_IDLE_S 30    /* idle time-out once the token was shown */

typedef struct ms_live_conn ms_live_conn;

typedef struct ms_live_guard {
    ms_live_conn *oldest, *newest;  /* the untrusted connections, by age */
    int untrusted;                  /* how many */
    unsigned long dropped;          /* connections the guard has closed */
} ms_live_guard;

/* libmicrohttpd's MHD_OPTION_NOTIFY_CONNECTION callback; cls is the guard. */
void ms_live_guard_notify(void *cls, struct MHD_Connection *c, void **socket_context,
                          enum MHD_ConnectionNotificationCode code);
/* c's request carries the token: trust the connection from now on. */
void ms_live_guard_trust(ms_live_guard *g, struct MHD_Connection *c);
/* Close the untrusted connections open for MS_LIVE_UNTRUSTED_S or more. Returns the
 * milliseconds until the next one is due, or -1 when none is open. */
long ms_live_guard_expire(ms_live_guard *g);

#endif
