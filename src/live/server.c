/* server.c: the live view's web server (live.h) on libmicrohttpd in its external epoll mode:
 * the daemon's epoll descriptor is a Tcl file handler and its timeouts a Tcl timer, so
 * requests are answered in molscope's own event loop, on the interpreter's thread, between
 * commands. libmicrohttpd parses HTTP and form bodies; this file only routes:
 *
 *   GET  /?token=T             the page (tcl/live/index.html of the Tcl library)
 *   GET  /state?token=T        {"serial":N,"passes":P,"maxpasses":M,"width":W,...,"version":V}
 *                              (JSON; V: the world's scene version, which /session gives too);
 *                              with &since=N, a long poll: the answer waits (the connection
 *                              suspended) until the image serial is no longer N, or 20 s
 *   GET  /image.png?token=T    the current image (headers X-Serial, X-Passes); with &since=N
 *                              a long poll like /state's, answered with the next image
 *   POST /view?token=T         form fields rx ry rz scale tx ty tz (live.h bounds)
 *   GET  /session?token=T      molecules, reps, trajectory and display settings (console.c)
 *   POST /tcl?token=T          form field cmd: a script run as at the prompt (lang=python:
 *                              Python code); the answer is console.c's JSON
 *   POST /cmd?token=T          form fields w (repeated): one command's words (the panels)
 *   POST /render?token=T       form fields method, file: `render <method> <file>`
 *   GET  /download?token=T     the file the last POST /render wrote
 *
 * The console and the panels run any command, as the terminal does: whoever holds the token
 * can run code as the user who started molscope (doc/SECURITY.md).
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
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#define ASSOC "molscope::live"
#define TOKEN_BYTES 16               /* 128 bits from /dev/urandom */
#define MAX_BODY 4096                /* a view change is a few dozen bytes */
#define MAX_FORM_BODY (1 << 20)      /* a console script or a command's words */
#define MAX_WAIT_MS 500              /* the longest the daemon waits to be run */
#define LONG_POLL_S 20.0             /* the longest a /state?since= request waits */

/* What a request keeps between the calls libmicrohttpd makes for it: the form a POST
 * gathers while its body arrives, or a long poll's place in the waiting list. */
typedef struct req_ctx {
    enum { REQ_VIEW = 1, REQ_FORM, REQ_WAIT } kind;
    /* REQ_VIEW, REQ_FORM */
    struct MHD_PostProcessor *pp;
    ms_live_view v;
    Tcl_Obj *fields;                 /* REQ_FORM: key value ... */
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
    int busy;                        /* inside a request: the daemon must not run again */
    int stop_requested;              /* `display live off` came from the page itself */
    char rendered[4096];             /* the file the last POST /render wrote */
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
             "\"version\":%lu,\"error\":\"%s\"}",
             f->serial, f->passes, f->max_passes, sv->app->world.width, sv->app->world.height,
             sv->app->world.scene_version, err);
    return reply(c, MHD_HTTP_OK, "application/json", json, strlen(json));
}

/* ---------------------------------------------------------------- requests */

static void on_timer(ClientData cd);
static void on_ready(ClientData cd, int mask);

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

/* The first call of a POST: its context, with a form parser that calls it. NULL with
 * *refused set when the body is not a form, or NULL alone when memory ran out. */
static req_ctx *post_begin(struct MHD_Connection *c, int kind, MHD_PostDataIterator it,
                           void **con_cls, int *refused)
{
    req_ctx *pc = calloc(1, sizeof *pc);
    if (!pc) return NULL;
    pc->kind = kind;
    ms_live_view_init(&pc->v);
    pc->pp = MHD_create_post_processor(c, 1024, it, pc);
    if (!pc->pp) {
        free(pc);
        *refused = 1;
        return NULL;
    }
    if (kind == REQ_FORM) Tcl_IncrRefCount(pc->fields = Tcl_NewListObj(0, NULL));
    *con_cls = pc;
    return pc;
}

/* A chunk of the body (size > 0: parsed, and 1 returned while more may come). */
static int post_feed(req_ctx *pc, const char *data, size_t *size, size_t max)
{
    if (!*size) return 0;
    pc->received += *size;
    if (pc->received > max) {
        ms_error_set(&pc->err, "body too large (over %zu bytes)", max);
        pc->bad = 1;
    }
    if (!pc->bad && MHD_post_process(pc->pp, data, *size) != MHD_YES) {
        ms_error_set(&pc->err, "malformed form body");
        pc->bad = 1;
    }
    *size = 0;
    return 1;
}

static enum MHD_Result refuse(struct MHD_Connection *c, const char *what, const req_ctx *pc)
{
    char msg[400];
    if (!pc) snprintf(msg, sizeof msg, "%s: expected an application/x-www-form-urlencoded body\n", what);
    else snprintf(msg, sizeof msg, "%s: refused: %.250s\n", what, pc->err.msg);
    return reply_text(c, MHD_HTTP_BAD_REQUEST, msg);
}

/* POST /view: gather the body, then apply it only when every field was valid. */
static enum MHD_Result on_view(live_server *sv, struct MHD_Connection *c, const char *data,
                               size_t *size, void **con_cls)
{
    req_ctx *pc = *con_cls;
    int refused = 0;
    if (!pc) {
        if (post_begin(c, REQ_VIEW, on_field, con_cls, &refused)) return MHD_YES;
        return refused ? refuse(c, "view", NULL) : MHD_NO;
    }
    if (post_feed(pc, data, size, MAX_BODY)) return MHD_YES;
    if (pc->bad) return refuse(c, "view", pc);
    ms_live_view_apply(sv->app, &pc->v);
    ms_live_frames_interact(&sv->frames);
    return reply(c, MHD_HTTP_OK, "application/json", "{\"ok\":true}", 11);
}

/* ---------------------------------------------------------------- console and panels */

/* A form field of /tcl /cmd /render: key and value appended, a value's later chunks
 * (off > 0) added to it. */
static enum MHD_Result on_form_field(void *cls, enum MHD_ValueKind kind, const char *key,
                                     const char *filename, const char *content_type,
                                     const char *transfer_encoding, const char *data,
                                     uint64_t off, size_t size)
{
    req_ctx *pc = cls;
    Tcl_Obj **v;
    int n = 0;
    Tcl_ListObjGetElements(NULL, pc->fields, &n, &v);
    if (off > 0 && n >= 2) {
        Tcl_AppendToObj(v[n - 1], data, (int)size);   /* held by the list alone */
        Tcl_InvalidateStringRep(pc->fields);
        return MHD_YES;
    }
    Tcl_ListObjAppendElement(NULL, pc->fields, Tcl_NewStringObj(key, -1));
    Tcl_ListObjAppendElement(NULL, pc->fields, Tcl_NewStringObj(data, (int)size));
    return MHD_YES;
}

/* The first value of key in the form, or NULL; with all, every value of key as a list. */
static Tcl_Obj *form_value(Tcl_Obj *fields, const char *key, int all)
{
    Tcl_Obj **v, *list = all ? Tcl_NewListObj(0, NULL) : NULL;
    int n = 0;
    Tcl_ListObjGetElements(NULL, fields, &n, &v);
    for (int i = 0; i + 1 < n; i += 2) {
        if (strcmp(Tcl_GetString(v[i]), key)) continue;
        if (!all) return v[i + 1];
        Tcl_ListObjAppendElement(NULL, list, v[i + 1]);
    }
    return list;
}

/* Run cmd for the page with the daemon held (a command that runs the event loop, such as
 * vwait or update, must not run it again inside this request) and answer its JSON. */
static enum MHD_Result answer_run(live_server *sv, struct MHD_Connection *c, Tcl_Obj *cmd,
                                  int as_words, const char *render_file)
{
    Tcl_DString json;
    Tcl_DStringInit(&json);
    sv->busy = 1;
    Tcl_DeleteFileHandler(sv->epoll_fd);
    int rc = ms_live_run(sv->app, cmd, as_words, &json);
    Tcl_CreateFileHandler(sv->epoll_fd, TCL_READABLE, on_ready, sv);
    sv->busy = 0;
    if (rc == 0 && render_file) snprintf(sv->rendered, sizeof sv->rendered, "%s", render_file);
    enum MHD_Result r = reply(c, MHD_HTTP_OK, "application/json", Tcl_DStringValue(&json),
                              (size_t)Tcl_DStringLength(&json));
    Tcl_DStringFree(&json);
    return r;
}

static enum MHD_Result run_form(live_server *sv, struct MHD_Connection *c, const char *url,
                                Tcl_Obj *fields)
{
    if (!strcmp(url, "/cmd")) return answer_run(sv, c, form_value(fields, "w", 1), 1, NULL);
    if (!strcmp(url, "/tcl")) {
        Tcl_Obj *code = form_value(fields, "cmd", 0), *lang = form_value(fields, "lang", 0);
        if (!code) return reply_text(c, MHD_HTTP_BAD_REQUEST, "tcl: no field cmd\n");
        if (!lang || !strcmp(Tcl_GetString(lang), "tcl")) return answer_run(sv, c, code, 0, NULL);
        if (strcmp(Tcl_GetString(lang), "python"))
            return reply_text(c, MHD_HTTP_BAD_REQUEST, "tcl: lang must be tcl or python\n");
        Tcl_Obj *words[2] = {Tcl_NewStringObj("::molscope::live::python", -1), code};
        return answer_run(sv, c, Tcl_NewListObj(2, words), 1, NULL);
    }
    Tcl_Obj *method = form_value(fields, "method", 0), *file = form_value(fields, "file", 0);
    if (!method || !file || !*Tcl_GetString(file))
        return reply_text(c, MHD_HTTP_BAD_REQUEST, "render: fields method and file are needed\n");
    Tcl_Obj *words[3] = {Tcl_NewStringObj("render", -1), method, file};
    return answer_run(sv, c, Tcl_NewListObj(3, words), 1, Tcl_GetString(file));
}

/* POST /tcl, /cmd, /render: gather the form, then run. */
static enum MHD_Result on_form(live_server *sv, struct MHD_Connection *c, const char *url,
                               const char *data, size_t *size, void **con_cls)
{
    req_ctx *pc = *con_cls;
    int refused = 0;
    if (!pc) {
        if (post_begin(c, REQ_FORM, on_form_field, con_cls, &refused)) return MHD_YES;
        return refused ? refuse(c, url + 1, NULL) : MHD_NO;
    }
    if (post_feed(pc, data, size, MAX_FORM_BODY)) return MHD_YES;
    if (pc->bad) return refuse(c, url + 1, pc);
    return run_form(sv, c, url, pc->fields);
}

/* GET /session: the panels' state. */
static enum MHD_Result on_session(live_server *sv, struct MHD_Connection *c)
{
    Tcl_DString json;
    ms_error err = {{0}};
    Tcl_DStringInit(&json);
    sv->busy = 1;
    int rc = ms_live_session_json(sv->app, sv->frames.raster_only, &json, &err);
    sv->busy = 0;
    enum MHD_Result r = rc ? reply_text(c, MHD_HTTP_INTERNAL_SERVER_ERROR, err.msg)
                           : reply(c, MHD_HTTP_OK, "application/json", Tcl_DStringValue(&json),
                                   (size_t)Tcl_DStringLength(&json));
    Tcl_DStringFree(&json);
    return r;
}

/* GET /download: the file of the last render from the page, as an attachment. */
static enum MHD_Result on_download(live_server *sv, struct MHD_Connection *c)
{
    struct stat sb;
    int fd = sv->rendered[0] ? open(sv->rendered, O_RDONLY) : -1;
    if (fd < 0 || fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        if (fd >= 0) close(fd);
        return reply_text(c, MHD_HTTP_NOT_FOUND, "download: nothing rendered from this page yet\n");
    }
    struct MHD_Response *r = MHD_create_response_from_fd((uint64_t)sb.st_size, fd);
    if (!r) {
        close(fd);
        return MHD_NO;
    }
    const char *base = strrchr(sv->rendered, '/');
    char disp[400], name[300];
    size_t k = 0;
    for (const char *p = base ? base + 1 : sv->rendered; *p && k + 1 < sizeof name; p++)
        name[k++] = (*p == '"' || *p == '\\' || (unsigned char)*p < 0x20) ? '_' : *p;
    name[k] = '\0';
    snprintf(disp, sizeof disp, "attachment; filename=\"%s\"", name);
    MHD_add_response_header(r, "Content-Disposition", disp);
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, "application/octet-stream");
    MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    enum MHD_Result rc = MHD_queue_response(c, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    return rc;
}

/* ---------------------------------------------------------------- long polls */

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

/* The current image, its serial and pass count in the headers X-Serial and X-Passes. */
static enum MHD_Result reply_image(live_server *sv, struct MHD_Connection *c)
{
    if (!sv->frames.png) return reply_text(c, MHD_HTTP_SERVICE_UNAVAILABLE, "no image yet\n");
    struct MHD_Response *r = MHD_create_response_from_buffer(sv->frames.png_len, sv->frames.png,
                                                             MHD_RESPMEM_MUST_COPY);
    if (!r) return MHD_NO;
    char serial[32], passes[32];
    snprintf(serial, sizeof serial, "%lu", sv->frames.serial);
    snprintf(passes, sizeof passes, "%d", sv->frames.passes);
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, "image/png");
    MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "X-Serial", serial);
    MHD_add_response_header(r, "X-Passes", passes);
    enum MHD_Result rc = MHD_queue_response(c, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    return rc;
}

/* GET /state and /image.png: at once, or (since= the current serial) suspended until
 * wake() resumes the request, which then gets the answer. */
static enum MHD_Result long_poll(live_server *sv, struct MHD_Connection *c, void **con_cls,
                                 enum MHD_Result (*answer)(live_server *, struct MHD_Connection *))
{
    const char *since = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "since");
    char *end;
    unsigned long n = since ? strtoul(since, &end, 10) : 0;
    if (*con_cls || !since || *end || n != sv->frames.serial) return answer(sv, c);
    req_ctx *w = calloc(1, sizeof *w);
    if (!w) return answer(sv, c);
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
    if (post && (!strcmp(url, "/tcl") || !strcmp(url, "/cmd") || !strcmp(url, "/render")))
        return on_form(sv, c, url, data, size, con_cls);
    if (!get)
        return reply_text(c, MHD_HTTP_METHOD_NOT_ALLOWED,
                          "only GET, and POST /view /tcl /cmd /render\n");
    if (!strcmp(url, "/") || !strcmp(url, "/index.html"))
        return reply(c, MHD_HTTP_OK, "text/html; charset=utf-8", sv->page, sv->page_len);
    if (!strcmp(url, "/state")) return long_poll(sv, c, con_cls, reply_state);
    if (!strcmp(url, "/image.png")) return long_poll(sv, c, con_cls, reply_image);
    if (!strcmp(url, "/session")) return on_session(sv, c);
    if (!strcmp(url, "/download")) return on_download(sv, c);
    return reply_text(c, MHD_HTTP_NOT_FOUND, "not found\n");
}

static void on_completed(void *cls, struct MHD_Connection *c, void **con_cls,
                         enum MHD_RequestTerminationCode toe)
{
    live_server *sv = cls;
    req_ctx *rc = *con_cls;
    if (!rc) return;
    if (rc->kind != REQ_WAIT) MHD_destroy_post_processor(rc->pp);
    if (rc->fields) Tcl_DecrRefCount(rc->fields);
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
    if (sv->busy) {                  /* the event loop runs inside a page's command */
        if (sv->timer) Tcl_DeleteTimerHandler(sv->timer);
        sv->timer = Tcl_CreateTimerHandler(MAX_WAIT_MS / 10, on_timer, sv);
        return;
    }
    resume_due(sv, 0);
    long due = ms_live_guard_expire(&sv->guard);
    MHD_run(sv->d);
    if (sv->stop_requested) {        /* `display live off` from the page, now answered */
        Tcl_DeleteAssocData(sv->app->interp, ASSOC);
        return;
    }
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
    snprintf(path, sizeof path, "%s/live/live.tcl", sv->app->tcllib_dir);
    Tcl_Obj *p = Tcl_NewStringObj(path, -1);
    Tcl_IncrRefCount(p);
    int rc = Tcl_FSEvalFileEx(sv->app->interp, p, "utf-8");
    Tcl_DecrRefCount(p);
    if (rc != TCL_OK) {
        ms_error_set(err, "cannot load %s: %.200s", path, Tcl_GetStringResult(sv->app->interp));
        Tcl_ResetResult(sv->app->interp);
        return -1;
    }
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
    if (sv->busy) {                  /* from the page: stop once its answer is queued */
        sv->stop_requested = 1;
        if (sv->timer) Tcl_DeleteTimerHandler(sv->timer);
        sv->timer = NULL;
        return 0;
    }
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
    memcpy(st->timing, sv->frames.timing, sizeof st->timing);
    st->triangles = sv->frames.triangles;
    st->coarse = sv->frames.coarse;
}

int ms_live_mode(ms_app *app, int set, int *raster_only)
{
    live_server *sv = server_of(app);
    if (!sv) return -1;
    if (set) ms_live_frames_set_raster(&sv->frames, *raster_only);
    *raster_only = sv->frames.raster_only;
    return 0;
}
