/* server.c: the live view's web server (live.h) on libmicrohttpd in its external epoll mode:
 * the daemon's epoll descriptor is a Tcl file handler and its timeouts a Tcl timer, so
 * requests are answered in molscope's own event loop, on the interpreter's thread, between
 * commands. libmicrohttpd parses HTTP and form bodies; this file only routes:
 *
 *   GET  /?token=T             the page (tcl/live/index.html of the Tcl library)
 *   GET  /state?token=T        {"serial":N,"passes":P,"maxpasses":M,"width":W,...} (JSON);
 *                              with &since=N, a long poll: the answer waits (the connection
 *                              suspended) until the image serial is no longer N, or 20 s
 *   GET  /image.png?token=T    the current image
 *   POST /view?token=T         form fields rx ry rz scale tx ty tz (live.h bounds)
 *
 * Every request without the token gets 403, whatever its path, as soon as its headers are
 * read, and its connection is closed. Connections that have not shown the token are
 * watched by guard.c (at most a few seconds each, and a few dozen at a time), so that no
 * local user without the token can hold the server's connections. The server's state is
 * the interpreter's associated data, so it stops when the interpreter is deleted at exit. */
#include "config.h"
#include "live/live.h"
#include "live/guard.h"

#include <arpa/inet.h>
#include <microhttpd.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tcl.h>
#include <unistd.h>

#define ASSOC "molscope::live"
#define TOKEN_BYTES 16               /* 128 bits from /dev/urandom */
#define MAX_BODY 4096                /* a view change is a few dozen bytes */
#define MAX_WAIT_MS 500              /* the longest the daemon waits to be run */
#define LONG_POLL_S 20.0             /* the longest a /state?since= request waits */

/* What a request keeps between the calls libmicrohttpd makes for it: the form a POST /view
 * gathers while its body arrives, or a long poll's place in the waiting list. */
typedef struct req_ctx {
    enum { REQ_VIEW = 1, REQ_WAIT } kind;
    /* REQ_VIEW */
    struct MHD_PostProcessor *pp;
    ms_live_view v;
    size_t received;
    int bad;
    ms_error err;
    /* REQ_WAIT */
    struct MHD_Connection *conn;
    unsigned long since;
    double deadline;
    struct req_ctx *next;
} req_ctx;

typedef struct live_server {
    ms_app *app;
    struct MHD_Daemon *d;
    int epoll_fd;
    Tcl_TimerToken timer;
    char token[2 * TOKEN_BYTES + 1];
    char url[300];
    int port;
    char *page;
    size_t page_len;
    ms_live_frames frames;
    req_ctx *waiting;                /* suspended long polls */
    ms_live_guard guard;             /* connections that have not shown the token */
} live_server;

static live_server *server_of(ms_app *app)
{
    return Tcl_GetAssocData(app->interp, ASSOC, NULL);
}

int ms_live_available(char *why, size_t size)
{
    if (size) why[0] = '\0';
    return 1;
}

/* ---------------------------------------------------------------- replies */

/* Queue a response; with close set the connection is closed once it is sent. */
static enum MHD_Result reply_on(struct MHD_Connection *c, unsigned status, const char *type,
                                const void *data, size_t len, int close)
{
    struct MHD_Response *r =
        MHD_create_response_from_buffer(len, (void *)data, MHD_RESPMEM_MUST_COPY);
    if (!r) return MHD_NO;
    if (close) MHD_add_response_header(r, MHD_HTTP_HEADER_CONNECTION, "close");
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, type);
    MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    enum MHD_Result rc = MHD_queue_response(c, status, r);
    MHD_destroy_response(r);
    return rc;
}

static enum MHD_Result reply(struct MHD_Connection *c, unsigned status, const char *type,
                             const void *data, size_t len)
{
    return reply_on(c, status, type, data, len, 0);
}

static enum MHD_Result reply_text(struct MHD_Connection *c, unsigned status, const char *text)
{
    return reply(c, status, "text/plain; charset=utf-8", text, strlen(text));
}

static enum MHD_Result reply_state(live_server *sv, struct MHD_Connection *c)
{
    char json[512], err[300];
    const ms_live_frames *f = &sv->frames;
    size_t k = 0;
    for (const char *p = f->error; *p && k + 2 < sizeof err; p++) {
        if (*p == '"' || *p == '\\') err[k++] = '\\';
        err[k++] = (unsigned char)*p < 0x20 ? ' ' : *p;
    }
    err[k] = '\0';
    snprintf(json, sizeof json,
             "{\"serial\":%lu,\"passes\":%d,\"maxpasses\":%d,\"width\":%d,\"height\":%d,"
             "\"error\":\"%s\"}",
             f->serial, f->passes, f->max_passes, sv->app->world.width, sv->app->world.height, err);
    return reply(c, MHD_HTTP_OK, "application/json", json, strlen(json));
}

/* ---------------------------------------------------------------- requests */

/* Whether the request names the server's token (compared in constant time). */
static int token_ok(const live_server *sv, struct MHD_Connection *c)
{
    const char *t = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "token");
    if (!t || strlen(t) != strlen(sv->token)) return 0;
    unsigned diff = 0;
    for (size_t i = 0; t[i]; i++) diff |= (unsigned char)(t[i] ^ sv->token[i]);
    return diff == 0;
}

static enum MHD_Result on_field(void *cls, enum MHD_ValueKind kind, const char *key,
                                const char *filename, const char *content_type,
                                const char *transfer_encoding, const char *data, uint64_t off,
                                size_t size)
{
    req_ctx *pc = cls;
    char value[64];
    if (pc->bad) return MHD_YES;
    if (off > 0 || size >= sizeof value) {
        ms_error_set(&pc->err, "%s: value too long", key);
        pc->bad = 1;
        return MHD_YES;
    }
    memcpy(value, data, size);
    value[size] = '\0';
    if (ms_live_view_set(&pc->v, key, value, &pc->err)) pc->bad = 1;
    return MHD_YES;
}

/* POST /view: gather the body, then apply it only when every field was valid. */
static enum MHD_Result on_view(live_server *sv, struct MHD_Connection *c, const char *data,
                               size_t *size, void **con_cls)
{
    req_ctx *pc = *con_cls;
    if (!pc) {
        if (!(pc = calloc(1, sizeof *pc))) return MHD_NO;
        pc->kind = REQ_VIEW;
        ms_live_view_init(&pc->v);
        pc->pp = MHD_create_post_processor(c, 1024, on_field, pc);
        if (!pc->pp) {
            free(pc);
            *con_cls = NULL;
            return reply_text(c, MHD_HTTP_BAD_REQUEST,
                              "view: expected an application/x-www-form-urlencoded body\n");
        }
        *con_cls = pc;
        return MHD_YES;
    }
    if (*size) {
        pc->received += *size;
        if (pc->received > MAX_BODY) {
            ms_error_set(&pc->err, "body too large");
            pc->bad = 1;
        }
        if (!pc->bad && MHD_post_process(pc->pp, data, *size) != MHD_YES) {
            ms_error_set(&pc->err, "malformed form body");
            pc->bad = 1;
        }
        *size = 0;
        return MHD_YES;
    }
    if (pc->bad) {
        char msg[300];
        snprintf(msg, sizeof msg, "view: refused: %.250s\n", pc->err.msg);
        return reply_text(c, MHD_HTTP_BAD_REQUEST, msg);
    }
    ms_live_view_apply(sv->app, &pc->v);
    ms_live_frames_kick(&sv->frames);
    return reply(c, MHD_HTTP_OK, "application/json", "{\"ok\":true}", 11);
}

/* ---------------------------------------------------------------- long polls */

static void on_timer(ClientData cd);

/* Resume the long polls whose answer is due: the image changed, their time is up, or all.
 * Returns how many were resumed (the daemon must run to answer them). */
static int resume_due(live_server *sv, int all)
{
    double now = ms_now();
    int n = 0;
    for (req_ctx **p = &sv->waiting; *p;) {
        req_ctx *w = *p;
        if (all || w->since != sv->frames.serial || now >= w->deadline) {
            *p = w->next;
            MHD_resume_connection(w->conn);
            n++;
        } else {
            p = &w->next;
        }
    }
    return n;
}

/* Resume what is due and have the daemon run at once when something was. */
static void wake(live_server *sv, int all)
{
    if (resume_due(sv, all) && sv->d) {
        if (sv->timer) Tcl_DeleteTimerHandler(sv->timer);
        sv->timer = Tcl_CreateTimerHandler(0, on_timer, sv);
    }
}

static void on_image(void *ud)
{
    wake(ud, 0);
}

/* GET /state: at once, or (since= the current serial) suspended until wake() resumes it. */
static enum MHD_Result on_state(live_server *sv, struct MHD_Connection *c, void **con_cls)
{
    const char *since = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "since");
    char *end;
    unsigned long n = since ? strtoul(since, &end, 10) : 0;
    if (*con_cls || !since || *end || n != sv->frames.serial) return reply_state(sv, c);
    req_ctx *w = calloc(1, sizeof *w);
    if (!w) return reply_state(sv, c);
    w->kind = REQ_WAIT;
    w->conn = c;
    w->since = n;
    w->deadline = ms_now() + LONG_POLL_S;
    w->next = sv->waiting;
    sv->waiting = w;
    *con_cls = w;
    MHD_suspend_connection(c);
    return MHD_YES;
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *c, const char *url,
                                  const char *method, const char *version,
                                  const char *data, size_t *size, void **con_cls)
{
    live_server *sv = cls;
    int get = !strcmp(method, MHD_HTTP_METHOD_GET) || !strcmp(method, MHD_HTTP_METHOD_HEAD);
    int post = !strcmp(method, MHD_HTTP_METHOD_POST);
    if (!*con_cls) {
        static const char no[] = "forbidden: this page needs its token\n";
        if (!token_ok(sv, c))
            return reply_on(c, MHD_HTTP_FORBIDDEN, "text/plain; charset=utf-8", no,
                            sizeof no - 1, 1);
        ms_live_guard_trust(&sv->guard, c);
    }
    if (post && !strcmp(url, "/view")) return on_view(sv, c, data, size, con_cls);
    if (!get)
        return reply_text(c, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET, and POST /view\n");
    if (!strcmp(url, "/") || !strcmp(url, "/index.html"))
        return reply(c, MHD_HTTP_OK, "text/html; charset=utf-8", sv->page, sv->page_len);
    if (!strcmp(url, "/state")) return on_state(sv, c, con_cls);
    if (!strcmp(url, "/image.png")) {
        if (!sv->frames.png) return reply_text(c, MHD_HTTP_SERVICE_UNAVAILABLE, "no image yet\n");
        return reply(c, MHD_HTTP_OK, "image/png", sv->frames.png, sv->frames.png_len);
    }
    return reply_text(c, MHD_HTTP_NOT_FOUND, "not found\n");
}

static void on_completed(void *cls, struct MHD_Connection *c, void **con_cls,
                         enum MHD_RequestTerminationCode toe)
{
    live_server *sv = cls;
    req_ctx *rc = *con_cls;
    if (!rc) return;
    if (rc->kind == REQ_VIEW) MHD_destroy_post_processor(rc->pp);
    for (req_ctx **p = &sv->waiting; *p; p = &(*p)->next)
        if (*p == rc) {
            *p = rc->next;
            break;
        }
    free(rc);
    *con_cls = NULL;
}

/* ---------------------------------------------------------------- the event loop */

/* Let the daemon do what is ready, then wake it again when its next timeout is due. */
static void pump(live_server *sv)
{
    resume_due(sv, 0);
    long due = ms_live_guard_expire(&sv->guard);
    MHD_run(sv->d);
    MHD_UNSIGNED_LONG_LONG ms = MAX_WAIT_MS;
    if (MHD_get_timeout(sv->d, &ms) != MHD_YES || ms > MAX_WAIT_MS) ms = MAX_WAIT_MS;
    if (due >= 0 && (MHD_UNSIGNED_LONG_LONG)due < ms) ms = (MHD_UNSIGNED_LONG_LONG)due;
    if (sv->timer) Tcl_DeleteTimerHandler(sv->timer);
    sv->timer = Tcl_CreateTimerHandler((int)ms, on_timer, sv);
}

static void on_timer(ClientData cd)
{
    live_server *sv = cd;
    sv->timer = NULL;
    pump(sv);
}

static void on_ready(ClientData cd, int mask)
{
    pump(cd);
}

/* ---------------------------------------------------------------- start and stop */

static void server_free(live_server *sv)
{
    if (sv->d) {
        Tcl_DeleteFileHandler(sv->epoll_fd);
        resume_due(sv, 1);           /* no connection may stay suspended at the stop */
        MHD_run(sv->d);
        MHD_stop_daemon(sv->d);
    }
    if (sv->timer) Tcl_DeleteTimerHandler(sv->timer);
    if (sv->frames.app) ms_live_frames_stop(&sv->frames);
    free(sv->page);
    free(sv);
}

static void on_interp_delete(ClientData cd, Tcl_Interp *interp)
{
    server_free(cd);
}

static int make_token(char *out, ms_error *err)
{
    unsigned char b[TOKEN_BYTES];
    FILE *f = fopen("/dev/urandom", "rb");
    int ok = f && fread(b, 1, sizeof b, f) == sizeof b;
    if (f) fclose(f);
    if (!ok) {
        ms_error_set(err, "cannot read /dev/urandom for the token");
        return -1;
    }
    for (int i = 0; i < TOKEN_BYTES; i++) sprintf(out + 2 * i, "%02x", b[i]);
    return 0;
}

static int load_page(live_server *sv, ms_error *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/live/index.html", sv->app->tcllib_dir);
    FILE *f = fopen(path, "rb");
    long n = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) n = ftell(f);
    if (n < 0 || n > (1L << 20) || fseek(f, 0, SEEK_SET) != 0 || !(sv->page = malloc((size_t)n + 1)) ||
        fread(sv->page, 1, (size_t)n, f) != (size_t)n) {
        if (f) fclose(f);
        ms_error_set(err, "cannot read the page %s", path);
        return -1;
    }
    fclose(f);
    sv->page_len = (size_t)n;
    return 0;
}

static int start_daemon(live_server *sv, int port, const char *addr, ms_error *err)
{
    struct sockaddr_in sa;
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    sa.sin_port = htons((uint16_t)port);
    if (inet_pton(AF_INET, addr, &sa.sin_addr) != 1) {
        ms_error_set(err, "'%s' is not an IPv4 address", addr);
        return -1;
    }
    sv->d = MHD_start_daemon(MHD_USE_EPOLL | MHD_ALLOW_SUSPEND_RESUME, 0, NULL, NULL, on_request, sv,
                             MHD_OPTION_SOCK_ADDR, (struct sockaddr *)&sa,
                             MHD_OPTION_CONNECTION_LIMIT, (unsigned)MS_LIVE_MAX_CONNECTIONS,
                             MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)MS_LIVE_UNTRUSTED_S,
                             MHD_OPTION_NOTIFY_CONNECTION, ms_live_guard_notify, &sv->guard,
                             MHD_OPTION_NOTIFY_COMPLETED, on_completed, sv, MHD_OPTION_END);
    if (!sv->d) {
        ms_error_set(err, "cannot listen on %s port %d (in use, or not an address of this machine)",
                     addr, port);
        return -1;
    }
    const union MHD_DaemonInfo *ep = MHD_get_daemon_info(sv->d, MHD_DAEMON_INFO_EPOLL_FD);
    const union MHD_DaemonInfo *pi = MHD_get_daemon_info(sv->d, MHD_DAEMON_INFO_BIND_PORT);
    if (!ep || !pi) {
        ms_error_set(err, "libmicrohttpd gave no epoll descriptor or port");
        return -1;
    }
    sv->epoll_fd = ep->epoll_fd;
    sv->port = pi->port;
    Tcl_CreateFileHandler(sv->epoll_fd, TCL_READABLE, on_ready, sv);
    return 0;
}

int ms_live_start(ms_app *app, int port, const char *bind_addr, ms_live_status *st,
                  ms_error *err)
{
    if (server_of(app)) {
        ms_error_set(err, "already on at %s", server_of(app)->url);
        return -1;
    }
    if (port < 0 || port > 65535) {
        ms_error_set(err, "port %d: expected 0 (any free port) to 65535", port);
        return -1;
    }
    const char *addr = bind_addr ? bind_addr : "127.0.0.1";
    live_server *sv = calloc(1, sizeof *sv);
    if (!sv) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    sv->app = app;
    if (make_token(sv->token, err) || load_page(sv, err) || start_daemon(sv, port, addr, err)) {
        server_free(sv);
        return -1;
    }
    char host[256];
    if (!strcmp(addr, "0.0.0.0") && gethostname(host, sizeof host) == 0) host[sizeof host - 1] = '\0';
    else snprintf(host, sizeof host, "%s", addr);
    snprintf(sv->url, sizeof sv->url, "http://%.200s:%d/?token=%s", host, sv->port, sv->token);
    ms_live_frames_start(&sv->frames, app);
    sv->frames.on_image = on_image;
    sv->frames.ud = sv;
    Tcl_SetAssocData(app->interp, ASSOC, on_interp_delete, sv);
    pump(sv);
    ms_live_get_status(app, st);
    return 0;
}

int ms_live_stop(ms_app *app)
{
    live_server *sv = server_of(app);
    if (!sv) return -1;
    Tcl_DeleteAssocData(app->interp, ASSOC);     /* calls on_interp_delete */
    return 0;
}

void ms_live_get_status(ms_app *app, ms_live_status *st)
{
    live_server *sv = server_of(app);
    memset(st, 0, sizeof *st);
    if (!sv) return;
    st->on = 1;
    snprintf(st->url, sizeof st->url, "%s", sv->url);
    st->port = sv->port;
    st->images = sv->frames.serial;
    st->passes = sv->frames.passes;
    snprintf(st->error, sizeof st->error, "%s", sv->frames.error);
}
