/* safewrite.c: the one implementation of molscope's output files (safewrite.h): follow the
 * name through symlinks, then either write a temporary file beside the final target and
 * rename it into place, or write a device, FIFO or descriptor in place. */
#include "config.h"
#include "base/safewrite.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/vfs.h>
#endif

#ifndef NAME_MAX
#define NAME_MAX 255
#endif

#define OFILE_MAX_LINKS 40     /* as the kernel's limit on a path's symlinks */
#define OFILE_TEMP_TRIES 100   /* fresh names tried while one exists already */
#define OFILE_RANDOM 8         /* random characters in a temporary name */
#define OFILE_TEMP_MARK ".tmp-"
#define OFILE_MAX_EXT 16       /* a longer "extension" is kept in the stem */
#define OFILE_PROC_MAGIC 0x9fa0 /* statfs's f_type of /proc */

struct ms_ofile {
    char *path;        /* the name the caller gave: every message names it */
    char *target;      /* the file the temporary replaces on commit; NULL when in place */
    char *tmp;         /* the temporary file; NULL when in place */
    int fd;            /* open for writing */
    FILE *fp;          /* ms_ofile_stream's stream over fd, or NULL */
    int werr;          /* errno of the first write that failed, 0 while none did */
    int sigpipe_held;  /* SIGPIPE blocked in this thread while a pipe is written */
    sigset_t old_mask; /* the thread's signal mask before */
    char fd_name[32];  /* "/dev/fd/N" */
};

/* What a name turned out to be once its symlinks were followed. */
enum { OF_MISSING, OF_REGULAR, OF_FOLDER, OF_OTHER, OF_DESCRIPTOR };

/* ---------------------------------------------------------------- names */

/* The base name of path (after the last slash). */
static const char *base_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* The folder part of path, "." when it has none (malloc'd). */
static char *folder_of(const char *path)
{
    const char *base = base_of(path);
    if (base == path) return ms_strdup(".");
    size_t n = (size_t)(base - path) - 1;
    return strndup(path, n ? n : 1);
}

/* The length of a base name's extension (".png"), 0 when it has none; a leading dot (a
 * hidden file) is no extension. */
static size_t ext_len(const char *base)
{
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return 0;
    size_t n = strlen(dot);
    return n <= OFILE_MAX_EXT ? n : 0;
}

/* How much of a base name's stem a temporary name keeps: all of it unless the temporary
 * name would pass NAME_MAX. */
static size_t stem_len(const char *base)
{
    size_t ext = ext_len(base), stem = strlen(base) - ext;
    size_t room = NAME_MAX - ext - (sizeof OFILE_TEMP_MARK - 1) - OFILE_RANDOM;
    return stem < room ? stem : room;
}

static uint64_t mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* n random characters from [A-Za-z0-9]: the kernel's randomness, or (where getrandom
 * fails) the clock, the process and a counter mixed. */
static void random_chars(char *out, size_t n)
{
    static const char set[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    static atomic_uint_fast64_t counter;
    unsigned char bytes[OFILE_RANDOM];
    if (n > sizeof bytes) n = sizeof bytes;
    if (getrandom(bytes, n, GRND_NONBLOCK) != (ssize_t)n) {
        struct timespec t;
        clock_gettime(CLOCK_REALTIME, &t);
        uint64_t x = mix64((uint64_t)t.tv_nsec ^ (uint64_t)t.tv_sec << 30 ^
                           (uint64_t)getpid() << 40 ^ atomic_fetch_add(&counter, 1));
        for (size_t i = 0; i < n; i++, x = mix64(x)) bytes[i] = (unsigned char)x;
    }
    for (size_t i = 0; i < n; i++) out[i] = set[bytes[i] % 62];
}

/* A fresh temporary name beside target: <folder/><stem>.tmp-XXXXXXXX<ext> (malloc'd). */
static char *temp_name(const char *target)
{
    const char *base = base_of(target);
    size_t dir = (size_t)(base - target), stem = stem_len(base), ext = ext_len(base);
    size_t mark = sizeof OFILE_TEMP_MARK - 1;
    char *name = malloc(dir + stem + mark + OFILE_RANDOM + ext + 1);
    if (!name) return NULL;
    char *p = name;
    memcpy(p, target, dir + stem);
    p += dir + stem;
    memcpy(p, OFILE_TEMP_MARK, mark);
    p += mark;
    random_chars(p, OFILE_RANDOM);
    p += OFILE_RANDOM;
    memcpy(p, base + strlen(base) - ext, ext + 1);
    return name;
}

int ms_ofile_is_temp(const char *name, const char *target)
{
    const char *base = base_of(target);
    size_t stem = stem_len(base), mark = sizeof OFILE_TEMP_MARK - 1;
    if (strncmp(name, base, stem) != 0 || strncmp(name + stem, OFILE_TEMP_MARK, mark) != 0)
        return 0;
    const char *r = name + stem + mark;
    for (int i = 0; i < OFILE_RANDOM; i++)
        if (!((r[i] >= 'A' && r[i] <= 'Z') || (r[i] >= 'a' && r[i] <= 'z') ||
              (r[i] >= '0' && r[i] <= '9')))
            return 0;
    return 1;
}

/* ---------------------------------------------------------------- following the name */

/* The name a symlink points to; a relative one is taken from the link's folder (malloc'd;
 * NULL with errno set). */
static char *link_target(const char *link)
{
    char *buf = NULL;
    for (size_t cap = 256;; cap *= 2) {
        if (cap > (1u << 16)) {
            errno = ENAMETOOLONG;
            return NULL;
        }
        char *b = realloc(buf, cap);
        if (!b) break;
        buf = b;
        ssize_t n = readlink(link, buf, cap);
        if (n < 0) break;
        if ((size_t)n >= cap) continue;
        buf[n] = '\0';
        const char *base = base_of(link);
        if (buf[0] == '/' || base == link) return buf;
        size_t dir = (size_t)(base - link), len = (size_t)n;
        char *full = malloc(dir + len + 1);
        if (full) {
            memcpy(full, link, dir);
            memcpy(full + dir, buf, len + 1);
        }
        free(buf);
        return full;
    }
    int e = errno;
    free(buf);
    errno = e ? e : ENOMEM;
    return NULL;
}

/* Whether a symlink lives in /proc: a process's descriptor (/dev/stdout leads to
 * /proc/self/fd/1), whose text ("pipe:[123]", a file's name) is no name to replace. */
static int on_proc(const char *link)
{
#ifdef __linux__
    char *dir = folder_of(link);
    struct statfs fs;
    int yes = dir && statfs(dir, &fs) == 0 && fs.f_type == OFILE_PROC_MAGIC;
    free(dir);
    return yes;
#else
    (void)link;
    return 0;
#endif
}

static int kind_of(const struct stat *st)
{
    if (S_ISLNK(st->st_mode)) return OF_DESCRIPTOR;
    if (S_ISREG(st->st_mode)) return OF_REGULAR;
    if (S_ISDIR(st->st_mode)) return OF_FOLDER;
    return OF_OTHER;
}

/* Follow path through its symlinks to the name to write: *final (malloc'd), its kind, and
 * in *st what lstat said of it. 0, or -1 with err set. */
static int resolve(const char *path, char **final, int *kind, struct stat *st, ms_error *err)
{
    char *cur = ms_strdup(path);
    errno = ENOMEM;
    for (int hops = 0; cur; hops++) {
        if (lstat(cur, st) != 0) {
            if (errno != ENOENT) break;
            *kind = OF_MISSING;
            *final = cur;
            return 0;
        }
        if (!S_ISLNK(st->st_mode) || on_proc(cur)) {
            *kind = kind_of(st);
            *final = cur;
            return 0;
        }
        char *next = hops < OFILE_MAX_LINKS ? link_target(cur) : (errno = ELOOP, NULL);
        int e = errno;
        free(cur);
        cur = next;
        errno = e;
    }
    int e = errno;
    free(cur);
    ms_error_set(err, "%s: cannot write: %s", path, strerror(e));
    return -1;
}

/* ---------------------------------------------------------------- opening */

/* Create a temporary file beside target with O_EXCL (never through a symlink); mode 0666
 * less the umask, as a plain creation. 0, or -1 with err set. */
static int create_temp(ms_ofile *o, const char *target, ms_error *err)
{
    for (int k = 0; k < OFILE_TEMP_TRIES; k++) {
        char *name = temp_name(target);
        if (!name) {
            ms_error_set(err, "%s: out of memory", o->path);
            return -1;
        }
        int fd = open(name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC,
                      0666);
        if (fd >= 0) {
            o->tmp = name;
            o->fd = fd;
            return 0;
        }
        int e = errno;
        free(name);
        if (e == EEXIST) continue;
        char *dir = folder_of(target);
        ms_error_set(err, "%s: cannot write: %s (in the folder %s)", o->path, strerror(e),
                     dir ? dir : ".");
        free(dir);
        return -1;
    }
    ms_error_set(err, "%s: cannot write: no free temporary name beside it", o->path);
    return -1;
}

/* Give the temporary file the owner (where allowed) and permissions of the file it will
 * replace. */
static void copy_owner_and_mode(int fd, const struct stat *st)
{
    if (st->st_uid != geteuid() || st->st_gid != getegid()) {
        if (fchown(fd, st->st_uid, st->st_gid) != 0 && fchown(fd, (uid_t)-1, st->st_gid) != 0) {
            /* another owner or group is not ours to give: the file becomes ours */
        }
    }
    if (fchmod(fd, st->st_mode & 0777) != 0) {
        /* the permissions of a new file stay: the contents are still replaced */
    }
}

/* A regular file (st) or a missing name: a temporary file to rename over target. */
static int open_replace(ms_ofile *o, const char *target, const struct stat *st, ms_error *err)
{
    const char *base = base_of(target);
    if (!*base || !strcmp(base, ".") || !strcmp(base, "..")) {
        ms_error_set(err, "%s: cannot write: %s", o->path, strerror(EISDIR));
        return -1;
    }
    /* A file we may not write stays as it is, as a plain open would leave it. */
    if (st && faccessat(AT_FDCWD, target, W_OK, AT_EACCESS) != 0) {
        ms_error_set(err, "%s: cannot write: %s", o->path, strerror(errno));
        return -1;
    }
    if (create_temp(o, target, err)) return -1;
    if (st) copy_owner_and_mode(o->fd, st);
    if (!(o->target = ms_strdup(target))) {
        ms_error_set(err, "%s: out of memory", o->path);
        return -1;
    }
    return 0;
}

/* While a FIFO, pipe or socket is written, SIGPIPE is blocked in this thread, so that a
 * reader that went away is a write error (EPIPE), not the end of molscope. Not when the
 * caller blocks it already. */
static void hold_sigpipe(ms_ofile *o)
{
    sigset_t pipe_sig;
    sigemptyset(&pipe_sig);
    sigaddset(&pipe_sig, SIGPIPE);
    if (pthread_sigmask(SIG_BLOCK, &pipe_sig, &o->old_mask) == 0)
        o->sigpipe_held = !sigismember(&o->old_mask, SIGPIPE);
}

/* Take back a SIGPIPE our writes raised, and restore the signal mask. */
static void release_sigpipe(ms_ofile *o)
{
    if (!o->sigpipe_held) return;
    sigset_t pipe_sig;
    sigemptyset(&pipe_sig);
    sigaddset(&pipe_sig, SIGPIPE);
    struct timespec zero = {0, 0};
    while (sigtimedwait(&pipe_sig, NULL, &zero) == SIGPIPE) {}
    pthread_sigmask(SIG_SETMASK, &o->old_mask, NULL);
    o->sigpipe_held = 0;
}

/* A device, FIFO, socket or descriptor: open it as it is, without creating or truncating.
 * 0, 1 when it became a regular file meanwhile (decide again), -1 with err set. */
static int open_in_place(ms_ofile *o, const char *name, int kind, ms_error *err)
{
    int fd = open(name, O_WRONLY | O_NOCTTY | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        ms_error_set(err, "%s: cannot write: %s", o->path, strerror(errno));
        if (fd >= 0) close(fd);
        return -1;
    }
    if (S_ISREG(st.st_mode) && kind != OF_DESCRIPTOR) {
        close(fd);
        return 1;
    }
    /* A descriptor's regular file (stdout redirected to a file) is written after what is
     * there, as the process's own output is. */
    if (S_ISREG(st.st_mode)) {
        int fl = fcntl(fd, F_GETFL);
        if (fl != -1) fcntl(fd, F_SETFL, fl | O_APPEND);
    }
    if (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)) hold_sigpipe(o);
    o->fd = fd;
    return 0;
}

/* A log's regular file or missing name: truncated or created where it is. */
static int open_log_file(ms_ofile *o, const char *name, ms_error *err)
{
    int fd = open(name, O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC, 0666);
    if (fd < 0) {
        ms_error_set(err, "%s: cannot write: %s", o->path, strerror(errno));
        return -1;
    }
    o->fd = fd;
    return 0;
}

/* One attempt: 0 opened, 1 the name changed under us (try again), -1 failed. */
static int open_once(ms_ofile *o, int log, ms_error *err)
{
    char *final;
    int kind, rc;
    struct stat st;
    if (resolve(o->path, &final, &kind, &st, err)) return -1;
    if (kind == OF_FOLDER) {
        ms_error_set(err, "%s: cannot write: %s", o->path, strerror(EISDIR));
        rc = -1;
    } else if (kind == OF_MISSING || kind == OF_REGULAR) {
        rc = log ? open_log_file(o, final, err)
                 : open_replace(o, final, kind == OF_REGULAR ? &st : NULL, err);
    } else {
        rc = open_in_place(o, final, kind, err);
    }
    free(final);
    return rc;
}

/* Close the stream and the descriptor; 0, or -1 with errno set. */
static int close_output(ms_ofile *o)
{
    int rc = o->fp ? fclose(o->fp) : 0;
    int e = errno;
    if (o->fd >= 0 && close(o->fd) != 0) rc = -1;
    else errno = e;
    o->fp = NULL;
    o->fd = -1;
    e = errno;
    release_sigpipe(o);
    errno = e;
    return rc;
}

static void ofile_free(ms_ofile *o)
{
    free(o->path);
    free(o->target);
    free(o->tmp);
    free(o);
}

static ms_ofile *open_output(const char *path, int log, ms_error *err)
{
    if (!path || !*path) {
        ms_error_set(err, "an empty file name");
        return NULL;
    }
    ms_ofile *o = calloc(1, sizeof *o);
    if (!o || !(o->path = ms_strdup(path))) {
        free(o);
        ms_error_set(err, "%s: out of memory", path);
        return NULL;
    }
    o->fd = -1;
    int rc = 1;
    for (int tries = 0; rc == 1 && tries < 3; tries++) rc = open_once(o, log, err);
    if (rc == 0) {
        snprintf(o->fd_name, sizeof o->fd_name, "/dev/fd/%d", o->fd);
        return o;
    }
    if (rc == 1)
        ms_error_set(err, "%s: cannot write: it kept changing while it was opened", path);
    close_output(o);
    if (o->tmp) unlink(o->tmp);
    ofile_free(o);
    return NULL;
}

ms_ofile *ms_ofile_open(const char *path, ms_error *err)
{
    return open_output(path, 0, err);
}

ms_ofile *ms_ofile_open_log(const char *path, ms_error *err)
{
    return open_output(path, 1, err);
}

/* ---------------------------------------------------------------- writing */

int ms_ofile_fd(const ms_ofile *o) { return o->fd; }
const char *ms_ofile_fd_name(const ms_ofile *o) { return o->fd_name; }
const char *ms_ofile_temp_name(const ms_ofile *o) { return o->tmp; }
const char *ms_ofile_path(const ms_ofile *o) { return o->path; }

/* write() all of n bytes to the descriptor; n, or less with o->werr set. */
static size_t write_fd(ms_ofile *o, const char *p, size_t n)
{
    size_t done = 0;
    while (done < n && !o->werr) {
        ssize_t w = write(o->fd, p + done, n - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) o->werr = w < 0 ? errno : EIO;
        else done += (size_t)w;
    }
    return done;
}

/* The stream's writes go through write_fd, so that the reason of a failure is kept. */
static ssize_t stream_write(void *cookie, const char *buf, size_t n)
{
    return (ssize_t)write_fd(cookie, buf, n);
}

FILE *ms_ofile_stream(ms_ofile *o, ms_error *err)
{
    if (o->fp) return o->fp;
    cookie_io_functions_t io = {.write = stream_write};
    if (!(o->fp = fopencookie(o, "wb", io))) {
        ms_error_set(err, "%s: cannot write: %s", o->path, strerror(errno));
        return NULL;
    }
    setvbuf(o->fp, NULL, _IOFBF, 1 << 16);
    return o->fp;
}

FILE *ms_ofile_open_stream(const char *path, ms_ofile **out, ms_error *err)
{
    *out = ms_ofile_open(path, err);
    FILE *fp = *out ? ms_ofile_stream(*out, err) : NULL;
    if (!fp) {
        ms_ofile_abort(*out);
        *out = NULL;
    }
    return fp;
}

static int write_error(const ms_ofile *o, int e, ms_error *err)
{
    ms_error_set(err, "%s: write error: %s", o->path, strerror(e ? e : EIO));
    return -1;
}

int ms_ofile_write(ms_ofile *o, const void *data, size_t n, ms_error *err)
{
    if (o->fp) return fwrite(data, 1, n, o->fp) == n ? 0 : write_error(o, o->werr, err);
    return write_fd(o, data, n) == n ? 0 : write_error(o, o->werr, err);
}

int ms_ofile_check(ms_ofile *o, ms_error *err)
{
    if (o->fp && fflush(o->fp) != 0 && !o->werr) o->werr = errno ? errno : EIO;
    if (o->fp && ferror(o->fp) && !o->werr) o->werr = EIO;
    return o->werr ? write_error(o, o->werr, err) : 0;
}

/* ---------------------------------------------------------------- finishing */

int ms_ofile_commit(ms_ofile *o, ms_error *err)
{
    int rc = ms_ofile_check(o, err);
    if (close_output(o) != 0 && rc == 0) rc = write_error(o, errno, err);
    if (rc == 0 && o->tmp && rename(o->tmp, o->target) != 0) {
        ms_error_set(err, "%s: cannot write: renaming the new file into place: %s", o->path,
                     strerror(errno));
        rc = -1;
    }
    if (rc && o->tmp) unlink(o->tmp);
    ofile_free(o);
    return rc;
}

void ms_ofile_abort(ms_ofile *o)
{
    if (!o) return;
    close_output(o);
    if (o->tmp) unlink(o->tmp);
    ofile_free(o);
}

int ms_ofile_finish(ms_ofile *o, int ok, ms_error *err)
{
    if (ok) return ms_ofile_commit(o, err);
    ms_ofile_abort(o);
    return -1;
}
