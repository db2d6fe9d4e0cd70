/* run.c: ms_movie_run, a whole movie job on every rank:
 *
 *   1. rank 0 plans: checks that the frames' (and video's) folders take files, removes the
 *      temporary files a killed job left, lists the frames still to render, looks for
 *      ffmpeg and starts it; the others wait (without spinning) and receive the plan;
 *   2. the frames still to render are handed out by ms_par_for_observed; each is rendered
 *      to a temporary file beside its name (base/safewrite), checked, and renamed; rank
 *      0's monitor learns of each completion and feeds the encoder in order;
 *   3. rank 0 waits for the encoder (the video is complete when the last frame is, plus
 *      the encoding of what was still queued), removes the frames when asked, and every
 *      rank receives the same outcome and the phase times of every rank. */
#include "config.h"
#include "movie/movie.h"
#include "parallel/parallel.h"
#include "base/safewrite.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static double epoch_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_REALTIME, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* ---------------------------------------------------------------- 1. the plan */

typedef struct plan {
    long *missing;           /* frames to render, ascending */
    long nmissing;
    ms_movie_encoder *enc;   /* rank 0, when a video is made */
    char note[1024];
} plan;

static int plan_rank0(const ms_movie_opts *o, plan *p, ms_error *err)
{
    int video = o->video && *o->video;
    if (ms_movie_check_dir(o->basename, err) || (video && ms_movie_check_dir(o->video, err)))
        return -1;
    ms_movie_remove_stale(o->basename, o->frame_format);
    if (video) ms_movie_remove_stale_video(o->video);
    if (ms_movie_scan(o->basename, o->frame_format, o->nframes, o->width, o->height, &p->missing,
                      &p->nmissing, err))
        return -1;
    if (!video) return 0;
    char *ffmpeg = ms_movie_find_ffmpeg();
    if (!ffmpeg) {
        const char *env = getenv("MOLSCOPE_FFMPEG");
        snprintf(p->note, sizeof p->note, "no video: %s%s%s is not there (install ffmpeg, "
                 "or set MOLSCOPE_FFMPEG to it); the frames are kept",
                 env && *env ? "MOLSCOPE_FFMPEG=" : "", env && *env ? env : "ffmpeg",
                 env && *env ? "" : " (on PATH)");
        fprintf(stderr, "movie: %s\n", p->note);
        return 0;
    }
    p->enc = ms_movie_encoder_start(ffmpeg, o, err);
    free(ffmpeg);
    return p->enc ? 0 : -1;
}

/* Rank 0's plan to every rank: {0, n, frames...} or {-1, message}. */
static int share_plan(plan *p, int rc, ms_error *err)
{
    ms_par_barrier(err); /* the others wait here while rank 0 scans, without spinning */
    if (ms_par_size() == 1) return rc;
    void *buf = NULL;
    size_t len = 0;
    if (ms_par_rank() == 0) {
        len = rc ? sizeof(int64_t) + strlen(err->msg) + 1
                 : (size_t)(p->nmissing + 2) * sizeof(int64_t);
        if (!(buf = malloc(len))) ms_par_abort(1, "movie: out of memory");
        int64_t *h = buf;
        h[0] = rc;
        if (rc) {
            strcpy((char *)(h + 1), err->msg);
        } else {
            h[1] = p->nmissing;
            for (long k = 0; k < p->nmissing; k++) h[2 + k] = p->missing[k];
        }
    }
    ms_par_bcast_buffer(&buf, &len, err);
    if (ms_par_rank() != 0) {
        const int64_t *h = buf;
        rc = (int)h[0];
        if (rc) {
            ms_error_set(err, "%s", (const char *)(h + 1));
        } else {
            p->nmissing = (long)h[1];
            p->missing = malloc((size_t)(p->nmissing ? p->nmissing : 1) * sizeof *p->missing);
            if (!p->missing) ms_par_abort(1, "movie: out of memory");
            for (long k = 0; k < p->nmissing; k++) p->missing[k] = (long)h[2 + k];
        }
    }
    free(buf);
    return rc;
}

/* ---------------------------------------------------------------- 2. the frames */

typedef struct loop_ctx {
    const ms_movie_opts *o;
    const long *missing;
    ms_movie_frame_fn fn;
    void *fn_ctx;
    ms_movie_monitor *mon;
    double busy;
    long rendered;
} loop_ctx;

/* Render frame into the temporary file of its output (a frame is read back, so it must
 * be a file), check it, and put it in place. */
static int render_frame(loop_ctx *c, long frame, ms_error *err)
{
    char *fin = ms_movie_frame_path(c->o->basename, c->o->frame_format, frame);
    ms_ofile *out = fin ? ms_ofile_open(fin, err) : NULL;
    const char *tmp = out ? ms_ofile_temp_name(out) : NULL;
    int ok = 0;
    if (!fin)
        ms_error_set(err, "out of memory");
    else if (out && !tmp)
        ms_error_set(err, "%s: a movie frame must be a file (not a device or a FIFO)", fin);
    else if (tmp && c->fn(c->fn_ctx, frame, tmp, err) == 0) {
        ok = ms_movie_frame_ok(tmp, c->o->width, c->o->height);
        if (!ok)
            ms_error_set(err, "the renderer wrote no complete %dx%d %s image to %s",
                         c->o->width, c->o->height,
                         c->o->frame_format == MS_FRAMES_RGB ? "SGI" : "PNG", tmp);
    }
    int rc = out ? ms_ofile_finish(out, ok, err) : -1;
    free(fin);
    return rc;
}

static int loop_item(void *ctx, long k, ms_error *err)
{
    loop_ctx *c = ctx;
    long frame = c->missing[k];
    double t = ms_now();
    int rc = render_frame(c, frame, err);
    c->busy += ms_now() - t;
    if (rc) {
        ms_error_prefix(err, "frame %ld", frame);
        return -1;
    }
    c->rendered++;
    return 0;
}

static void loop_done(void *ctx, long k)
{
    loop_ctx *c = ctx;
    ms_movie_monitor_done(c->mon, c->missing[k]);
}

/* ---------------------------------------------------------------- 3. the outcome */

typedef struct rank_rec {
    double started, script_done, run_start, busy;
    int64_t rendered;
} rank_rec;

typedef struct summary {
    int64_t rc, video_made;
    double render_s, tail_s, end;
    char note[1024], err[1024];
} summary;

/* Every rank's record and rank 0's summary, to every rank; fills st. */
static int gather(const rank_rec *mine, summary *sum, ms_movie_stats *st, ms_error *err)
{
    ms_par_barrier(err); /* the others wait here while rank 0 finishes the video */
    ms_par_parts parts;
    if (ms_par_allgather(mine, sizeof *mine, &parts, err)) return -1;
    void *buf = sum;
    size_t len = sizeof *sum;
    ms_par_bcast_buffer(&buf, &len, err);
    if (buf != sum) {
        memcpy(sum, buf, sizeof *sum);
        free(buf);
    }
    double first_start = -1;
    for (int r = 0; r < parts.n; r++) {
        rank_rec x;
        memcpy(&x, parts.data + parts.off[r], sizeof x);
        double script = x.started >= 0 && x.script_done >= 0 ? x.script_done - x.started : 0;
        double state = x.script_done >= 0 ? x.run_start - x.script_done : 0;
        if (r == 0) {
            st->script_s = script;
            st->state_s = state;
        }
        st->script_max_s = MS_MAX(st->script_max_s, script);
        st->state_max_s = MS_MAX(st->state_max_s, state);
        st->busy_max_s = MS_MAX(st->busy_max_s, x.busy);
        st->busy_sum_s += x.busy;
        st->rendered += (long)x.rendered;
        double s0 = x.started >= 0 ? x.started : x.run_start;
        if (first_start < 0 || s0 < first_start) first_start = s0;
    }
    ms_par_parts_free(&parts);
    st->ranks = ms_par_size();
    st->render_s = sum->render_s;
    st->encode_tail_s = sum->tail_s;
    st->total_s = sum->end - first_start;
    st->video_made = (int)sum->video_made;
    snprintf(st->note, sizeof st->note, "%s", sum->note);
    return 0;
}

static void remove_frames(const ms_movie_opts *o)
{
    for (long i = 0; i < o->nframes; i++) {
        char *p = ms_movie_frame_path(o->basename, o->frame_format, i);
        if (p) unlink(p);
        free(p);
    }
}

/* Rank 0 after the loop: the video, the frames, the summary. */
static void finish_rank0(const ms_movie_opts *o, plan *p, ms_movie_monitor *mon, double t0,
                         summary *sum)
{
    ms_error e = {{0}};
    double last = t0;
    int rc = ms_movie_monitor_finish(mon, 1, &last, &e);
    double now = ms_now();
    sum->render_s = last - t0;
    sum->tail_s = now - last;
    sum->end = epoch_now();
    sum->video_made = p->enc && rc == 0;
    if (rc) {
        sum->rc = -1;
        snprintf(sum->err, sizeof sum->err, "video %.300s: %.680s; the frames are kept", o->video,
                 e.msg);
    }
    snprintf(sum->note, sizeof sum->note, "%s", p->note);
    if (sum->video_made && !o->keep_frames) remove_frames(o);
}

int ms_movie_run(const ms_movie_opts *o, ms_movie_frame_fn fn, void *ctx,
                 ms_movie_stats *st, ms_error *err)
{
    memset(st, 0, sizeof *st);
    st->frames = o->nframes;
    double t0 = ms_now();
    rank_rec mine = {o->started, o->script_done, epoch_now(), 0, 0};
    plan p = {0};
    int rc = ms_par_rank() == 0 ? plan_rank0(o, &p, err) : 0;
    if (rc && p.enc) ms_movie_encoder_finish(p.enc, 0, NULL);
    if ((rc = share_plan(&p, rc, err))) {
        free(p.missing);
        return -1;
    }
    st->reused = o->nframes - p.nmissing;
    loop_ctx c = {o, p.missing, fn, ctx, NULL, 0, 0};
    if (ms_par_rank() == 0) {
        uint8_t *done = malloc((size_t)(o->nframes ? o->nframes : 1));
        if (done) {
            memset(done, 1, (size_t)o->nframes);
            for (long k = 0; k < p.nmissing; k++) done[p.missing[k]] = 0;
            c.mon = ms_movie_monitor_start(o, done, p.nmissing, p.enc, err);
            free(done);
        } else {
            ms_error_set(err, "out of memory");
        }
        if (!c.mon) {
            if (p.enc) ms_movie_encoder_finish(p.enc, 0, NULL);
            if (ms_par_size() > 1) ms_par_abort(1, "movie: %s", err->msg);
            free(p.missing);
            return -1;
        }
    }
    rc = ms_par_for_observed(0, p.nmissing - 1, loop_item, &c, loop_done, &c, "movie make",
                             err);
    if (rc) { /* one rank (with several, a failed frame has ended the job) */
        ms_movie_monitor_finish(c.mon, 0, NULL, NULL);
        free(p.missing);
        return -1;
    }
    mine.busy = c.busy;
    mine.rendered = c.rendered;
    summary sum = {0};
    if (ms_par_rank() == 0) finish_rank0(o, &p, c.mon, t0, &sum);
    free(p.missing);
    if (gather(&mine, &sum, st, err)) return -1;
    if (sum.rc) {
        ms_error_set(err, "%s", sum.err);
        return -1;
    }
    return 0;
}
