/* encoder.c: the video encoder, an ffmpeg subprocess fed raw RGB frames through a pipe.
 * ffmpeg is GPL software: molscope only runs it as a program (posix_spawn), never links it.
 * The codec is H.264 (libx264), MPEG-1, -2 or -4, or an animated GIF (ms_movie_codec).
 * It writes the video's output opened by base/safewrite: the temporary file beside the
 * video, renamed over it when ffmpeg succeeded (or a device or FIFO, written in place); its
 * messages go to a deleted temporary file and the last of them become the error when it
 * fails. */
#include "config.h"
#include "movie/movie.h"
#include "base/safewrite.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

struct ms_movie_encoder {
    pid_t pid;
    int in;              /* ffmpeg's standard input */
    int log;             /* ffmpeg's standard error */
    size_t frame_bytes;
    ms_ofile *out;       /* the video's output */
};

static char *find_on_path(const char *name)
{
    if (strchr(name, '/')) return access(name, X_OK) == 0 ? ms_strdup(name) : NULL;
    const char *path = getenv("PATH");
    if (!path) path = "/usr/bin:/bin";
    for (const char *p = path;;) {
        const char *end = strchr(p, ':');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        char *cand = malloc(n + strlen(name) + 2);
        if (!cand) return NULL;
        snprintf(cand, n + strlen(name) + 2, "%.*s/%s", (int)n, n ? p : ".", name);
        struct stat sb;
        if (stat(cand, &sb) == 0 && S_ISREG(sb.st_mode) && access(cand, X_OK) == 0) return cand;
        free(cand);
        if (!end) return NULL;
        p = end + 1;
    }
}

char *ms_movie_find_ffmpeg(void)
{
    const char *env = getenv("MOLSCOPE_FFMPEG");
    if (env && *env) return find_on_path(env);
    char *p = find_on_path("ffmpeg");
#ifdef MS_FFMPEG_PATH
    if (!p) p = find_on_path(MS_FFMPEG_PATH);
#endif
    return p;
}

/* The extension of video's base name (".mp4"), or NULL when it has none. */
static const char *video_ext(const char *video)
{
    const char *slash = strrchr(video, '/');
    const char *base = slash ? slash + 1 : video;
    const char *dot = strrchr(base, '.');
    return dot && dot != base && dot[1] ? dot : NULL;
}

/* The last lines ffmpeg wrote (at most size - 1 bytes, newlines as "; "). */
static void log_tail(int fd, char *buf, size_t size)
{
    buf[0] = '\0';
    off_t end = lseek(fd, 0, SEEK_END);
    if (end <= 0) return;
    off_t from = end > (off_t)(size - 1) ? end - (off_t)(size - 1) : 0;
    ssize_t n = pread(fd, buf, (size_t)(end - from), from);
    if (n <= 0) return;
    buf[n] = '\0';
    while (n > 0 && (buf[n - 1] == '\n' || buf[n - 1] == '\r' || buf[n - 1] == ' ')) buf[--n] = '\0';
    for (char *p = buf; *p; p++)
        if (*p == '\n' || *p == '\r') *p = ';';
}

static int spawn(ms_movie_encoder *e, const char *ffmpeg, char *const argv[], ms_error *err)
{
    int fds[2];
    char logname[] = "/tmp/molscope-ffmpeg-XXXXXX";
    e->log = mkostemp(logname, O_CLOEXEC);
    if (e->log < 0 || pipe2(fds, O_CLOEXEC) != 0) {
        ms_error_set(err, "cannot start ffmpeg: %s", strerror(errno));
        if (e->log >= 0) {
            unlink(logname);
            close(e->log);
            e->log = -1;
        }
        return -1;
    }
    unlink(logname);
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, e->log, 2);
    posix_spawnattr_init(&at);
    sigset_t none, pipe_sig;
    sigemptyset(&none);
    sigemptyset(&pipe_sig);
    sigaddset(&pipe_sig, SIGPIPE);
    posix_spawnattr_setsigmask(&at, &none);
    posix_spawnattr_setsigdefault(&at, &pipe_sig);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    int rc = posix_spawn(&e->pid, ffmpeg, &fa, &at, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    close(fds[0]);
    if (rc != 0) {
        close(fds[1]);
        ms_error_set(err, "cannot run %s: %s", ffmpeg, strerror(rc));
        return -1;
    }
    e->in = fds[1];
    return 0;
}

int ms_movie_preset_ok(const char *name)
{
    static const char *const presets[] = {"ultrafast", "superfast", "veryfast", "faster",
                                          "fast", "medium", "slow", "slower", "veryslow",
                                          "placebo"};
    for (size_t i = 0; i < MS_COUNTOF(presets); i++)
        if (!strcmp(name, presets[i])) return 1;
    return 0;
}

/* The text of ffmpeg's options that hold numbers (kept alive while argv is used). */
typedef struct codec_text {
    char size[32], rate[32], q[16], pad[64], bitrate[32];
} codec_text;

/* Append to argv (from *n) the options of o's codec: the encoder, its quality and the
 * pixel format (with the padding of odd sizes), or the GIF's palette filter. */
static void codec_args(const ms_movie_opts *o, const char *preset, codec_text *t,
                       const char **argv, int *n)
{
    static const char *const enc[] = {"libx264", "mpeg1video", "mpeg2video", "mpeg4", "gif"};
    snprintf(t->q, sizeof t->q, "%d", o->crf);
    snprintf(t->bitrate, sizeof t->bitrate, "%ld", o->bitrate > 0 ? o->bitrate : 8000000L);
    snprintf(t->pad, sizeof t->pad, "pad=%d:%d", o->width + (o->width & 1),
             o->height + (o->height & 1));
    argv[(*n)++] = "-c:v";
    argv[(*n)++] = enc[o->codec];
    if (o->codec == MS_CODEC_GIF) {
        argv[(*n)++] = "-vf";
        argv[(*n)++] = "split[a][b];[a]palettegen[p];[b][p]paletteuse";
        return;
    }
    if (o->codec == MS_CODEC_H264) {
        const char *x264[] = {"-preset", preset, "-crf", t->q};
        for (size_t k = 0; k < MS_COUNTOF(x264); k++) argv[(*n)++] = x264[k];
    } else {
        argv[(*n)++] = "-b:v";
        argv[(*n)++] = t->bitrate;
    }
    argv[(*n)++] = "-pix_fmt";
    argv[(*n)++] = "yuv420p";
    if ((o->width | o->height) & 1) {
        argv[(*n)++] = "-vf";
        argv[(*n)++] = t->pad;
    }
}

ms_movie_encoder *ms_movie_encoder_start(const char *ffmpeg, const ms_movie_opts *o,
                                         ms_error *err)
{
    const char *preset = o->preset ? o->preset : "veryfast";
    if (!ms_movie_preset_ok(preset)) {
        ms_error_set(err, "unknown x264 preset '%s'", preset);
        return NULL;
    }
    const char *ext = video_ext(o->video);
    if (!ext) {
        ms_error_set(err, "%s: the video's name needs an extension that names its format "
                          "(.mp4, .mkv, .mov ...)", o->video);
        return NULL;
    }
    ms_movie_encoder *e = calloc(1, sizeof *e);
    if (!e) {
        ms_error_set(err, "out of memory");
        return NULL;
    }
    e->in = e->log = -1;
    e->frame_bytes = (size_t)o->width * (size_t)o->height * 3;
    if (!(e->out = ms_ofile_open(o->video, err))) goto fail;
    /* ffmpeg opens its output by name: the temporary file, or the device or FIFO itself. */
    const char *dest = ms_ofile_temp_name(e->out) ? ms_ofile_temp_name(e->out) : o->video;
    codec_text t;
    snprintf(t.size, sizeof t.size, "%dx%d", o->width, o->height);
    snprintf(t.rate, sizeof t.rate, "%.6g", o->fps);
    int mp4 = !strcasecmp(ext, ".mp4") || !strcasecmp(ext, ".mov") || !strcasecmp(ext, ".m4v");
    const char *argv[40];
    int n = 0;
    const char *head[] = {"ffmpeg", "-hide_banner", "-nostats", "-loglevel", "error", "-y",
                          "-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size", t.size,
                          "-framerate", t.rate, "-i", "pipe:0", "-an"};
    for (size_t k = 0; k < MS_COUNTOF(head); k++) argv[n++] = head[k];
    codec_args(o, preset, &t, argv, &n);
    if (mp4) {
        argv[n++] = "-movflags";
        argv[n++] = "+faststart";
    }
    argv[n++] = dest;
    argv[n] = NULL;
    if (spawn(e, ffmpeg, (char *const *)argv, err) == 0) return e;
fail:
    ms_ofile_abort(e->out);
    free(e);
    return NULL;
}

/* write() everything, with SIGPIPE blocked in this thread: a gone reader is EPIPE, not the
 * end of molscope (a SIGPIPE raised here stays pending on this thread; it is taken back). */
static int write_all(int fd, const uint8_t *p, size_t n)
{
    sigset_t pipe_sig, old;
    sigemptyset(&pipe_sig);
    sigaddset(&pipe_sig, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_sig, &old);
    int rc = 0;
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            rc = -1;
            break;
        }
        p += w;
        n -= (size_t)w;
    }
    if (rc && errno == EPIPE) {
        struct timespec zero = {0, 0};
        int saved = errno;
        sigtimedwait(&pipe_sig, NULL, &zero);
        errno = saved;
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc;
}

int ms_movie_encoder_put(ms_movie_encoder *e, const uint8_t *rgb, ms_error *err)
{
    if (write_all(e->in, rgb, e->frame_bytes) == 0) return 0;
    int saved = errno;
    char tail[600];
    usleep(100000); /* let a dying ffmpeg finish its message */
    log_tail(e->log, tail, sizeof tail);
    ms_error_set(err, "ffmpeg stopped reading frames (%s)%s%s", strerror(saved),
                 tail[0] ? ": " : "", tail);
    return -1;
}

int ms_movie_encoder_finish(ms_movie_encoder *e, int ok, ms_error *err)
{
    /* err is only written when ok is set: callers dropping the video may pass NULL. */
    if (e->in >= 0) close(e->in);
    if (!ok) kill(e->pid, SIGTERM);
    int status = 0, rc = 0;
    while (waitpid(e->pid, &status, 0) < 0 && errno == EINTR) {}
    if (ok && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
        char tail[600];
        log_tail(e->log, tail, sizeof tail);
        if (WIFEXITED(status))
            ms_error_set(err, "ffmpeg failed (exit status %d)%s%s", WEXITSTATUS(status),
                         tail[0] ? ": " : "", tail);
        else
            ms_error_set(err, "ffmpeg was killed by signal %d", WTERMSIG(status));
        rc = -1;
    }
    if (ok && rc == 0) rc = ms_ofile_commit(e->out, err);
    else ms_ofile_abort(e->out);
    close(e->log);
    free(e);
    return rc;
}
