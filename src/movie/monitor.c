/* monitor.c: rank 0's movie thread. The loop tells it when each frame completes (on any
 * rank); it feeds the encoder in frame order, as soon as the next frame in order exists
 * (frames finished out of order wait for the ones before them), and prints progress: done
 * of total, frames per minute and the time left. It makes no MPI call and never touches the
 * Tcl interpreter. */
#include "config.h"
#include "image/image.h"
#include "movie/movie.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct ms_movie_monitor {
    char *basename;
    ms_movie_frames format;
    long nframes, todo, reused;
    int width, height;
    int progress;            /* 0 off, 1 a line per wake-up, 2 every 5 %, 3 in place */
    uint8_t *done;           /* per frame */
    long next;               /* the next frame for the encoder */
    long ndone;              /* frames completed by this run */
    ms_movie_encoder *enc;
    int enc_failed;
    ms_error enc_err;
    int finishing, aborting;
    double t0, t_last, last_print;
    long last_step, last_shown;   /* the 5 % step and the count last printed */
    pthread_mutex_t lock;
    pthread_cond_t cond;
    pthread_t th;
};

/* Read frame i back (waiting a little for a file another node has just renamed) and give
 * it to the encoder. */
static int feed(ms_movie_monitor *m, long i, ms_error *err)
{
    char *path = ms_movie_frame_path(m->basename, m->format, i);
    if (!path) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    ms_image img = {0};
    int rc = -1;
    for (int tries = 0; tries < 50; tries++) {
        rc = ms_image_read(path, &img, err);
        if (rc == 0 || access(path, F_OK) == 0) break;
        usleep(100000);
    }
    if (rc == 0 && (img.width != m->width || img.height != m->height)) {
        ms_error_set(err, "%s is %dx%d, not %dx%d", path, img.width, img.height, m->width,
                     m->height);
        rc = -1;
    }
    if (rc == 0) rc = ms_movie_encoder_put(m->enc, img.rgb, err);
    else ms_error_prefix(err, "frame %ld", i);
    ms_image_free(&img);
    free(path);
    return rc;
}

static void fmt_time(double s, char *buf, size_t size)
{
    long t = (long)(s + 0.5);
    if (t >= 3600) snprintf(buf, size, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else snprintf(buf, size, "%ld:%02ld", t / 60, t % 60);
}

/* Print progress when due. Caller holds the lock. */
static void report(ms_movie_monitor *m)
{
    if (!m->progress || m->todo == 0 || m->ndone == 0 || m->ndone == m->last_shown) return;
    double now = ms_now(), el = now - m->t0;
    int last = m->ndone == m->todo;
    long step = m->ndone * 20 / m->todo;
    if (m->progress == 2 && step == m->last_step && !last) return;
    if (m->progress == 3 && now - m->last_print < 0.25 && !last) return;
    m->last_step = step;
    m->last_shown = m->ndone;
    m->last_print = now;
    double fpm = el > 0 ? m->ndone * 60.0 / el : 0;
    char left[32] = "?";
    if (m->ndone > 0) fmt_time((double)(m->todo - m->ndone) * el / (double)m->ndone, left, sizeof left);
    char reused[48] = "";
    if (m->reused) snprintf(reused, sizeof reused, " (%ld reused)", m->reused);
    int tty = m->progress == 3;
    fprintf(stderr, "%smovie: %ld/%ld frames%s, %.1f frames/min, %s left%s", tty ? "\r" : "",
            m->reused + m->ndone, m->nframes, reused, fpm, left,
            !tty ? "\n" : last ? "\033[K\n" : "\033[K");
    fflush(stderr);
}

static void *monitor_main(void *arg)
{
    ms_movie_monitor *m = arg;
    pthread_mutex_lock(&m->lock);
    for (;;) {
        while (!m->aborting && m->enc && !m->enc_failed && m->next < m->nframes &&
               m->done[m->next]) {
            long i = m->next;
            pthread_mutex_unlock(&m->lock);
            ms_error e = {{0}};
            int rc = feed(m, i, &e);
            pthread_mutex_lock(&m->lock);
            if (rc) {
                m->enc_failed = 1;
                m->enc_err = e;
            }
            m->next++;
        }
        report(m);
        if (m->aborting) break;
        if (m->finishing && (!m->enc || m->enc_failed || m->next >= m->nframes)) break;
        pthread_cond_wait(&m->cond, &m->lock);
    }
    pthread_mutex_unlock(&m->lock);
    return NULL;
}

ms_movie_monitor *ms_movie_monitor_start(const ms_movie_opts *o, const uint8_t *done,
                                         long todo, ms_movie_encoder *enc, ms_error *err)
{
    ms_movie_monitor *m = calloc(1, sizeof *m);
    if (!m || !(m->basename = ms_strdup(o->basename)) ||
        !(m->done = malloc((size_t)o->nframes ? (size_t)o->nframes : 1))) {
        if (m) free(m->basename);
        free(m);
        ms_error_set(err, "out of memory");
        return NULL;
    }
    memcpy(m->done, done, (size_t)o->nframes);
    m->format = o->frame_format;
    m->nframes = o->nframes;
    m->todo = todo;
    m->reused = o->nframes - todo;
    m->width = o->width;
    m->height = o->height;
    m->progress = o->progress < 0 ? (isatty(2) ? 3 : 2) : o->progress ? 1 : 0;
    m->last_step = -1;
    m->enc = enc;
    m->t0 = m->t_last = ms_now();
    pthread_mutex_init(&m->lock, NULL);
    pthread_cond_init(&m->cond, NULL);
    if (pthread_create(&m->th, NULL, monitor_main, m) != 0) {
        pthread_mutex_destroy(&m->lock);
        pthread_cond_destroy(&m->cond);
        free(m->done);
        free(m->basename);
        free(m);
        ms_error_set(err, "cannot start a thread");
        return NULL;
    }
    return m;
}

void ms_movie_monitor_done(void *monitor, long i)
{
    ms_movie_monitor *m = monitor;
    pthread_mutex_lock(&m->lock);
    if (i >= 0 && i < m->nframes && !m->done[i]) {
        m->done[i] = 1;
        m->ndone++;
        m->t_last = ms_now();
    }
    pthread_cond_signal(&m->cond);
    pthread_mutex_unlock(&m->lock);
}

int ms_movie_monitor_finish(ms_movie_monitor *m, int ok, double *last_done_at,
                            ms_error *err)
{
    pthread_mutex_lock(&m->lock);
    if (ok) m->finishing = 1;
    else m->aborting = 1;
    pthread_cond_signal(&m->cond);
    pthread_mutex_unlock(&m->lock);
    pthread_join(m->th, NULL);
    if (m->progress == 3 && m->last_shown > 0 && m->last_shown < m->todo)
        fputc('\n', stderr); /* end the line updated in place */
    int rc = 0;
    ms_error e = {{0}};
    if (m->enc_failed) {
        e = m->enc_err;
        rc = -1;
    }
    if (m->enc && ms_movie_encoder_finish(m->enc, ok && !m->enc_failed, &e) == -1) rc = -1;
    if (rc && err) *err = e;
    if (last_done_at) *last_done_at = m->t_last;
    pthread_mutex_destroy(&m->lock);
    pthread_cond_destroy(&m->cond);
    free(m->done);
    free(m->basename);
    free(m);
    return rc;
}
