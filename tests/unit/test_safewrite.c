/* test_safewrite.c: base/safewrite, the output files every writer uses: a new file, a
 * regular file replaced whole (mode kept), symlinks written through (chains, dangling
 * links, links to devices), a FIFO and /dev/null written in place, /dev/full's error, a
 * descriptor (/proc/self/fd/N, /dev/stdout), an unwritable folder and a read-only file,
 * abort, and symlinks planted at the temporary names earlier versions used. */
#include "config.h"
#include "ms_test.h"
#include "base/safewrite.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[900];

/* dir/name in a static buffer (one of four, so a few can be alive at once). */
static const char *at(const char *name)
{
    static char bufs[4][1200];
    static int k;
    char *b = bufs[k++ % 4];
    snprintf(b, sizeof bufs[0], "%s/%s", dir, name);
    return b;
}

/* The whole of a file as a string (malloc'd; "" when it cannot be read). */
static char *slurp(const char *path)
{
    char *buf = calloc(1, 1 << 20);
    FILE *f = fopen(path, "rb");
    if (f && buf) {
        size_t n = fread(buf, 1, (1 << 20) - 1, f);
        buf[n] = '\0';
    }
    if (f) fclose(f);
    return buf;
}

static int has(const char *path, const char *want)
{
    char *got = slurp(path);
    int yes = got && !strcmp(got, want);
    free(got);
    return yes;
}

static void put(const char *path, const char *data, mode_t mode)
{
    unlink(path);
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(data, f);
        fclose(f);
    }
    chmod(path, mode);
}

/* Files in folder d whose names contain ".tmp" or ".part" (any writer's temporary). */
static int temps_in(const char *d)
{
    DIR *dp = opendir(d);
    int n = 0;
    for (struct dirent *e; dp && (e = readdir(dp));)
        n += strstr(e->d_name, ".tmp") || strstr(e->d_name, ".part");
    if (dp) closedir(dp);
    return n;
}

static int entries_in(const char *d)
{
    DIR *dp = opendir(d);
    int n = 0;
    for (struct dirent *e; dp && (e = readdir(dp));)
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    if (dp) closedir(dp);
    return n;
}

/* Open, write data (through the stream), commit: what commit returned. */
static int write_through(const char *path, const char *data, ms_error *err)
{
    ms_ofile *o = ms_ofile_open(path, err);
    FILE *f = o ? ms_ofile_stream(o, err) : NULL;
    if (!f) {
        ms_ofile_abort(o);
        return -1;
    }
    fputs(data, f);
    return ms_ofile_commit(o, err);
}

static int is_link_to(const char *link, const char *want)
{
    char buf[1200];
    struct stat st;
    ssize_t n = lstat(link, &st) == 0 && S_ISLNK(st.st_mode) ? readlink(link, buf, sizeof buf - 1)
                                                             : -1;
    if (n < 0) return 0;
    buf[n] = '\0';
    return !strcmp(buf, want);
}

/* ---------------------------------------------------------------- regular files */

static void test_new_and_replace(void)
{
    ms_error err = {{0}};
    int rc = write_through(at("new.txt"), "fresh\n", &err);
    struct stat st = {0};
    t_ok(rc == 0 && has(at("new.txt"), "fresh\n"), "a new file is written (%s)", err.msg);
    stat(at("new.txt"), &st);
    t_ok((st.st_mode & 0777) == 0644, "a new file has 0666 less the umask (022): %o",
         (unsigned)(st.st_mode & 0777));

    put(at("old.txt"), "old contents\n", 0640);
    struct stat before, after;
    stat(at("old.txt"), &before);
    ms_ofile *o = ms_ofile_open(at("old.txt"), &err);
    FILE *f = o ? ms_ofile_stream(o, &err) : NULL;
    if (f) fputs("new contents\n", f);
    if (f) fflush(f);
    t_ok(o && has(at("old.txt"), "old contents\n"),
         "while it is written, the file keeps its old contents");
    t_ok(o && ms_ofile_commit(o, &err) == 0 && has(at("old.txt"), "new contents\n"),
         "a regular file is replaced (%s)", err.msg);
    memset(&after, 0, sizeof after);
    stat(at("old.txt"), &after);
    t_ok((after.st_mode & 0777) == 0640, "... its mode (0640) is kept: %o",
         (unsigned)(after.st_mode & 0777));
    t_ok(after.st_ino != before.st_ino, "... by a rename (a new inode), not rewritten in place");
    t_ok(temps_in(dir) == 0, "no temporary file is left");
}

static void test_abort(void)
{
    ms_error err = {{0}};
    put(at("keep.txt"), "keep me\n", 0644);
    ms_ofile *o = ms_ofile_open(at("keep.txt"), &err);
    t_ok(o && ms_ofile_write(o, "garbage", 7, &err) == 0, "write before an abort");
    ms_ofile_abort(o);
    t_ok(has(at("keep.txt"), "keep me\n"), "abort leaves the file exactly as it was");
    o = ms_ofile_open(at("never.txt"), &err);
    if (o) ms_ofile_write(o, "x", 1, &err);
    ms_ofile_abort(o);
    t_ok(access(at("never.txt"), F_OK) != 0, "abort of a new file creates nothing");
    t_ok(temps_in(dir) == 0, "abort leaves no temporary file");
    t_ok(ms_ofile_finish(ms_ofile_open(at("keep.txt"), &err), 0, &err) == -1 &&
             has(at("keep.txt"), "keep me\n"),
         "finish(ok = 0) is an abort");
}

static void test_names(void)
{
    ms_error err = {{0}};
    ms_ofile *o = ms_ofile_open(at("a.b.png"), &err);
    const char *tmp = o ? ms_ofile_temp_name(o) : NULL;
    const char *base = tmp ? strrchr(tmp, '/') + 1 : "";
    size_t n = strlen(base);
    t_ok(tmp && !strncmp(base, "a.b.tmp-", 8) && n > 4 && !strcmp(base + n - 4, ".png"),
         "the temporary name keeps the extension: %s", base);
    t_ok(ms_ofile_is_temp(base, "a.b.png") && !ms_ofile_is_temp("a.b.png", "a.b.png") &&
             !ms_ofile_is_temp(base, "a.c.png"),
         "ms_ofile_is_temp knows its own names");
    /* A program opening the descriptor's name reaches the temporary file. */
    FILE *f = o ? fopen(ms_ofile_fd_name(o), "wb") : NULL;
    if (f) {
        fputs("by name\n", f);
        fclose(f);
    }
    t_ok(f && ms_ofile_commit(o, &err) == 0 && has(at("a.b.png"), "by name\n"),
         "writing /dev/fd/N by name reaches the output (%s)", err.msg);

    char longname[300];
    memset(longname, 'x', 250);
    memcpy(longname + 250, ".png", 5);
    t_ok(write_through(at(longname), "long\n", &err) == 0 && has(at(longname), "long\n"),
         "a 254-character name still gets a temporary name (%s)", err.msg);
    unlink(at(longname));
}

/* ---------------------------------------------------------------- symlinks */

static void test_symlinks(void)
{
    ms_error err = {{0}};
    put(at("real.txt"), "before\n", 0600);
    symlink("real.txt", at("link.txt"));
    symlink("link.txt", at("link2.txt"));
    int rc = write_through(at("link.txt"), "through the link\n", &err);
    t_ok(rc == 0 && is_link_to(at("link.txt"), "real.txt"), "a symlink stays the same link (%s)",
         err.msg);
    struct stat st;
    t_ok(has(at("real.txt"), "through the link\n") && stat(at("real.txt"), &st) == 0 &&
             (st.st_mode & 0777) == 0600,
         "... its target is replaced, its mode (0600) kept");
    rc = write_through(at("link2.txt"), "two links\n", &err);
    t_ok(rc == 0 && is_link_to(at("link2.txt"), "link.txt") &&
             is_link_to(at("link.txt"), "real.txt") && has(at("real.txt"), "two links\n"),
         "a chain of symlinks: both stay, the final target is replaced (%s)", err.msg);

    symlink("made.txt", at("dangling.txt"));
    rc = write_through(at("dangling.txt"), "created\n", &err);
    t_ok(rc == 0 && is_link_to(at("dangling.txt"), "made.txt") && has(at("made.txt"), "created\n"),
         "a dangling symlink: the file it names is created, the link stays (%s)", err.msg);

    /* A link into another folder: the temporary file is made beside the target. */
    mkdir(at("elsewhere"), 0755);
    put(at("elsewhere/far.txt"), "far\n", 0644);
    symlink(at("elsewhere/far.txt"), at("far-link.txt"));
    rc = write_through(at("far-link.txt"), "replaced far away\n", &err);
    t_ok(rc == 0 && has(at("elsewhere/far.txt"), "replaced far away\n") &&
             is_link_to(at("far-link.txt"), at("elsewhere/far.txt")) &&
             temps_in(at("elsewhere")) == 0 && temps_in(dir) == 0,
         "an absolute link into another folder (%s)", err.msg);

    symlink("loop-b", at("loop-a"));
    symlink("loop-a", at("loop-b"));
    t_ok(ms_ofile_open(at("loop-a"), &err) == NULL && strstr(err.msg, "loop-a") &&
             strstr(err.msg, strerror(ELOOP)),
         "a loop of links is an error naming it (%s)", err.msg);
}

/* ---------------------------------------------------------------- in place */

static void test_fifo(void)
{
    ms_error err = {{0}};
    const char *fifo = at("pipe.fifo");
    int rd = mkfifo(fifo, 0644) == 0 ? open(fifo, O_RDONLY | O_NONBLOCK) : -1;
    if (rd < 0) {
        t_skip("FIFO", strerror(errno));
        return;
    }
    /* The reader is there before the write (which is small enough for the pipe's buffer),
     * so the write does not wait for it, and a FIFO replaced by a file reads as empty. */
    int rc = write_through(fifo, "into the fifo\n", &err);
    char got[256] = {0};
    ssize_t n = read(rd, got, sizeof got - 1);
    close(rd);
    struct stat st;
    t_ok(rc == 0 && n == 14 && !strcmp(got, "into the fifo\n"),
         "a FIFO's reader gets the bytes (%s)", err.msg);
    t_ok(lstat(fifo, &st) == 0 && S_ISFIFO(st.st_mode), "... and the FIFO is still a FIFO");
    t_ok(temps_in(dir) == 0, "... with no temporary file beside it");

    /* A reader that goes away: a write error naming the path, and this process lives on
     * (SIGPIPE would end it). */
    rd = open(fifo, O_RDONLY | O_NONBLOCK);
    ms_ofile *o = rd >= 0 ? ms_ofile_open(fifo, &err) : NULL;
    close(rd);
    t_ok(o && ms_ofile_write(o, "nobody reads", 12, &err) == -1 &&
             strstr(err.msg, "pipe.fifo") && strstr(err.msg, strerror(EPIPE)),
         "a FIFO whose reader left: an error naming it, not SIGPIPE (%s)", err.msg);
    ms_ofile_abort(o);
    sigset_t mask;
    pthread_sigmask(SIG_BLOCK, NULL, &mask);
    t_ok(!sigismember(&mask, SIGPIPE), "... and SIGPIPE is unblocked again afterwards");
}

static int same_node(const struct stat *a, const char *path)
{
    struct stat b;
    return lstat(path, &b) == 0 && S_ISCHR(b.st_mode) && b.st_ino == a->st_ino &&
           b.st_rdev == a->st_rdev;
}

static int dev_temps(void)
{
    DIR *dp = opendir("/dev");
    int n = 0;
    for (struct dirent *e; dp && (e = readdir(dp));)
        n += (!strncmp(e->d_name, "null", 4) || !strncmp(e->d_name, "full", 4)) &&
             (strstr(e->d_name, ".tmp") || strstr(e->d_name, ".part"));
    if (dp) closedir(dp);
    return n;
}

static void test_devices(void)
{
    ms_error err = {{0}};
    struct stat null0, full0;
    if (lstat("/dev/null", &null0) != 0 || !S_ISCHR(null0.st_mode) ||
        lstat("/dev/full", &full0) != 0 || !S_ISCHR(full0.st_mode)) {
        t_skip("devices", "no /dev/null or /dev/full character device here");
        return;
    }
    static char big[200000];
    memset(big, 'x', sizeof big - 1);
    int rc = write_through("/dev/null", big, &err);
    t_ok(rc == 0 && same_node(&null0, "/dev/null"), "/dev/null is written in place (%s)", err.msg);

    rc = write_through("/dev/full", big, &err);
    t_ok(rc == -1 && !strncmp(err.msg, "/dev/full: ", 11) && strstr(err.msg, strerror(ENOSPC)),
         "/dev/full: an error naming the path and the reason (%s)", err.msg);
    ms_ofile *o = ms_ofile_open("/dev/full", &err);
    err.msg[0] = '\0';
    t_ok(o && ms_ofile_write(o, "x", 1, &err) == -1 && strstr(err.msg, "/dev/full"),
         "/dev/full through the descriptor: the write fails at once (%s)", err.msg);
    ms_ofile_abort(o);
    t_ok(same_node(&full0, "/dev/full"), "... and /dev/full is still the device");
    t_ok(dev_temps() == 0, "nothing was created in /dev");

    symlink("/dev/null", at("null-link"));
    err.msg[0] = '\0';
    rc = write_through(at("null-link"), "to a link to a device\n", &err);
    t_ok(rc == 0 && is_link_to(at("null-link"), "/dev/null") && same_node(&null0, "/dev/null"),
         "a symlink to /dev/null: written through, link and device stay (%s)", err.msg);
}

static void test_descriptors(void)
{
    ms_error err = {{0}};
    int p[2];
    char name[64], got[64] = {0};
    if (pipe(p) != 0 || access("/proc/self/fd", F_OK) != 0) {
        t_skip("descriptors", "no pipe or no /proc");
        return;
    }
    snprintf(name, sizeof name, "/proc/self/fd/%d", p[1]);
    int rc = write_through(name, "down the pipe", &err);
    close(p[1]);
    ssize_t n = read(p[0], got, sizeof got - 1);
    close(p[0]);
    t_ok(rc == 0 && n == 13 && !strcmp(got, "down the pipe"),
         "/proc/self/fd/N of a pipe is written in place (%s)", err.msg);

    /* stdout redirected to a file: /dev/stdout appends to it, the file is not replaced. */
    const char *log = at("stdout.log");
    put(log, "", 0644);
    int fd = open(log, O_WRONLY | O_TRUNC);
    if (write(fd, "head\n", 5) != 5) fd = -1;
    struct stat before, after;
    fstat(fd, &before);
    fflush(stdout);
    int saved = dup(1);
    dup2(fd, 1);
    rc = write_through("/dev/stdout", "tail\n", &err);
    dup2(saved, 1);
    close(saved);
    close(fd);
    t_ok(rc == 0 && has(log, "head\ntail\n") && stat(log, &after) == 0 &&
             after.st_ino == before.st_ino,
         "/dev/stdout redirected to a file: appended to it in place (%s)", err.msg);
}

/* ---------------------------------------------------------------- refusals */

static void test_errors(void)
{
    ms_error err = {{0}};
    t_ok(ms_ofile_open(at("nope/x.txt"), &err) == NULL && strstr(err.msg, "nope/x.txt") &&
             strstr(err.msg, "No such file"),
         "a missing folder is an error naming the path (%s)", err.msg);
    t_ok(ms_ofile_open(dir, &err) == NULL && strstr(err.msg, strerror(EISDIR)),
         "a folder is an error (%s)", err.msg);
    t_ok(ms_ofile_open(at("newdir/"), &err) == NULL, "a name ending in / is an error (%s)",
         err.msg);
    t_ok(access(at("newdir"), F_OK) != 0, "... and creates nothing");
    t_ok(ms_ofile_open("", &err) == NULL, "an empty name is an error (%s)", err.msg);
}

/* The checks an unprivileged user makes: bit 0 the folder refused, bit 1 nothing created
 * in it, bit 2 a read-only file refused, bit 3 it is untouched; 64 when the folder cannot
 * be reached at all (the test is then skipped). */
static int unprivileged_checks(void)
{
    if (access(dir, X_OK) != 0) return 64;
    ms_error err = {{0}};
    int bits = 0;
    if (!ms_ofile_open(at("ro/x.txt"), &err) && strstr(err.msg, "ro/x.txt") &&
        strstr(err.msg, strerror(EACCES)))
        bits |= 1;
    if (entries_in(at("ro")) == 0) bits |= 2;
    if (!ms_ofile_open(at("rw/locked.txt"), &err) && strstr(err.msg, "locked.txt")) bits |= 4;
    if (has(at("rw/locked.txt"), "locked\n")) bits |= 8;
    return bits;
}

static void test_permissions(void)
{
    mkdir(at("ro"), 0555);
    chmod(at("ro"), 0555);
    mkdir(at("rw"), 0777);
    chmod(at("rw"), 0777);
    put(at("rw/locked.txt"), "locked\n", 0444);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        /* root writes anywhere: the checks run as nobody */
        if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) _exit(65);
        _exit(unprivileged_checks());
    }
    int status = 0;
    waitpid(pid, &status, 0);
    int bits = WIFEXITED(status) ? WEXITSTATUS(status) : 0;
    if (bits >= 64) {
        t_skip("unwritable folder", bits == 64 ? "the test folder is not reachable as nobody"
                                               : "cannot become nobody");
        return;
    }
    t_ok(bits & 1, "an unwritable folder is an error naming the path (Permission denied)");
    t_ok(bits & 2, "... and nothing is created in it");
    t_ok(bits & 4, "a read-only file is refused, as a plain open refuses it");
    t_ok(bits & 8, "... and left untouched");
}

/* ---------------------------------------------------------------- planted symlinks */

/* Symlinks at every temporary name earlier versions made for target (their names hold
 * the process id, or are fixed): each points at a victim, which must survive. */
static void test_planted(void)
{
    ms_error err = {{0}};
    mkdir(at("victims"), 0755);
    put(at("victims/precious.txt"), "precious\n", 0644);
    const char *victim = at("victims/precious.txt");
    char names[4][1200];
    long pid = (long)getpid();
    snprintf(names[0], sizeof names[0], "%s/out.png.tmp%ld", dir, pid);   /* image, write.c */
    snprintf(names[1], sizeof names[1], "%s/out.png.%ld.tmp", dir, pid);  /* OpenCL cache */
    snprintf(names[2], sizeof names[2], "%s/out.part.png", dir);          /* video, frames */
    snprintf(names[3], sizeof names[3], "%s/out.png.tmp%ld", dir, pid + 1);
    for (int k = 0; k < 4; k++) symlink(victim, names[k]);
    int rc = write_through(at("out.png"), "the output\n", &err);
    int links_ok = 1;
    for (int k = 0; k < 4; k++) links_ok &= is_link_to(names[k], victim);
    t_ok(rc == 0 && has(at("out.png"), "the output\n"), "the output is written (%s)", err.msg);
    t_ok(has(victim, "precious\n"), "a victim behind symlinks at the old temporary names is untouched");
    t_ok(links_ok, "... and the planted links are left alone");
    for (int k = 0; k < 4; k++) unlink(names[k]);
}

int main(void)
{
    t_suite = "safewrite";
    umask(022);
    snprintf(dir, sizeof dir, "%s/safewrite", getenv("MS_TEST_OUT") ? getenv("MS_TEST_OUT")
                                                                      : "/tmp");
    char cmd[2 * sizeof dir + 64];
    snprintf(cmd, sizeof cmd, "chmod -R u+w '%s' 2>/dev/null; rm -rf '%s'", dir, dir);
    if (system(cmd) != 0) { /* nothing there yet */ }
    if (mkdir(dir, 0777) != 0 || chmod(dir, 0777) != 0) {
        t_ok(0, "make the folder %s: %s", dir, strerror(errno));
        return t_done();
    }
    test_new_and_replace();
    test_abort();
    test_names();
    test_symlinks();
    test_fifo();
    test_devices();
    test_descriptors();
    test_errors();
    test_permissions();
    test_planted();
    return t_done();
}
