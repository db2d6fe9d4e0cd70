/* frame.c: rendering a frame progressively. Memory is planned first (the float accumulation
 * buffer and the pixels' random states; what is left bounds Embree's build), the world is
 * built, then each pass adds one sample to every pixel (sample.c says where): 16 x 16 tiles
 * spread over all threads by ms_parallel_for, with flush-to-zero and denormals-are-zero on
 * while they trace. A render traces each pixel's passes one after another, tile by tile:
 * a pixel's samples hit about the same point, and their rays walk the same part of the trees,
 * which is then still in the caches (3-20% of the CPU time on issue 21's benchmarks). The
 * picture is the one of pass after pass over the whole frame, each pixel's samples, random
 * numbers and sums coming in the same order. A time budget (checked after each pass) and the
 * live view's sessions trace pass after pass over the frame. A pass limit or a time budget
 * may end the frame early; the average of the passes becomes the image, which is written
 * through image/image.h. */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/threads.h"
#include "render/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#define TILE 16

typedef struct frame {
    const rt_shader *sh;
    int width, height, tiles_x, pass, depth;
    int passes;                 /* each pixel traces passes pass .. pass + passes - 1 */
    size_t tile0;               /* the first tile of the round being traced */
    float *accum;               /* 3 floats per pixel: sums of the samples */
    uint32_t *rng;              /* per-pixel random state, kept from pass to pass */
    uint64_t (*rays)[MS_RT_NRAYKINDS];  /* per thread */
    rt_raydump *dump;           /* MOLSCOPE_RT_RAYDUMP's file, or NULL */
} frame;

/* A tile's pixels, each its passes f->pass .. f->pass + f->passes - 1 in turn. */
static void trace_tile(const frame *f, rt_thread *th, size_t tile)
{
    int x0 = (int)(tile % (size_t)f->tiles_x) * TILE, y0 = (int)(tile / (size_t)f->tiles_x) * TILE;
    int x1 = MS_MIN(x0 + TILE, f->width), y1 = MS_MIN(y0 + TILE, f->height);
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            size_t idx = (size_t)y * (size_t)f->width + (size_t)x;
            float *a = f->accum + 3 * idx;
            th->rng = f->rng[idx];
            for (int pass = f->pass; pass < f->pass + f->passes; pass++) {
                float sx, sy, lens[2], org[3], dir[3], col[3];
                rt_sample_pixel((uint32_t)idx, pass, &sx, &sy);
                int lensed = pass > 0 && f->sh->cam.dof;
                if (lensed) rt_sample_disc(&th->rng, lens);
                else if (pass > 0) rt_rand(&th->rng), rt_rand(&th->rng);  /* the lens numbers, unused: the stream stays */
                rt_camera_ray(&f->sh->cam, (float)x + sx, (float)y + sy, lensed ? lens : NULL, org, dir);
                rt_trace(f->sh, th, org, dir, f->depth, 1, col);
                for (int k = 0; k < 3; k++) a[k] += isfinite(col[k]) ? col[k] : 0.0f;   /* a degenerate camera */
            }
            f->rng[idx] = th->rng;
        }
}

static void trace_tiles(void *ctx, size_t b, size_t e, int thread)
{
    frame *f = ctx;
    unsigned fpu = rt_fpu_fast();
    rt_thread th;
    memset(&th, 0, sizeof th);
    rtcInitIntersectContext(&th.ctx.ec);
    th.dump = rt_raydump_buf(f->dump, thread);
    for (size_t t = f->tile0 + b; t < f->tile0 + e; t++) trace_tile(f, &th, t);
    for (int k = 0; k < MS_RT_NRAYKINDS; k++) f->rays[thread][k] += th.rays[k];
    rt_fpu_restore(fpu);
}

/* ---------------------------------------------------------------- checks and memory */


/* Room for the frame's buffers, then for Embree (90% of what is available): an error when
 * the buffers alone do not fit. */
int rt_plan_memory(const ms_scene *s, const ms_rt_options *o, ms_error *err)
{
    size_t npix = (size_t)s->width * (size_t)s->height;
    size_t need = npix * (3 * sizeof(float) + sizeof(uint32_t) + 3);
    size_t avail = o->memory ? o->memory : ms_mem_available();
    if (avail && need > avail / 10 * 9) {
        ms_error_set(err, "a %dx%d image needs %.2f GB for its buffers, more than the %.2f GB of "
                     "memory available: a smaller image (display resize) would fit", s->width,
                     s->height, (double)need / 1e9, (double)avail / 1e9);
        return -1;
    }
    size_t room = avail ? avail / 10 * 9 - need : 0, ntris, nother;
    size_t placed = rt_place_bytes(s);      /* the lists' world-space copies, beside Embree */
    size_t est = rt_world_estimate(s, &ntris, &nother) + placed;
    if (avail && est > room) {
        ms_error_set(err, "the scene is too large: the ray tracer's acceleration structures "
                     "need at least %.2f GB for "
                     "%zu triangles and %zu other primitives, more than the %.2f GB of memory "
                     "available beside the %dx%d image's buffers: a coarser QuickSurf grid "
                     "spacing, fewer atoms drawn or a smaller image would fit",
                     (double)est / 1e9, ntris, nother, (double)room / 1e9, s->width, s->height);
        return -1;
    }
    rt_device_set_budget(avail ? room - placed : 0);
    return 0;
}

/* ---------------------------------------------------------------- passes */

/* CPU seconds of the process so far, all threads. */
static double cpu_now(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

/* A line on stderr: what of the frame is done (what: "pass 3/13", "40% of 13 passes"). */
static void progress(const ms_rt_stats *st, const char *what, double t0)
{
    double el = ms_now() - t0;
    fprintf(stderr, "TachyonInternal: %s, %.1f s, %.1f Mrays/s\n", what, el,
            el > 0 ? (double)ms_rt_stats_rays(st) / el / 1e6 : 0.0);
}

static size_t frame_tiles(const frame *f)
{
    return (size_t)f->tiles_x * (size_t)((f->height + TILE - 1) / TILE);
}

/* Tiles [t0, t1), each pixel its passes f->pass .. f->pass + f->passes - 1; the counts of
 * rays so far into st. */
static void trace_round(frame *f, size_t t0, size_t t1, ms_rt_stats *st)
{
    f->tile0 = t0;
    ms_parallel_for(t1 - t0, 1, trace_tiles, f);
    rt_raydump_flush(f->dump);
    memset(st->rays, 0, sizeof st->rays);
    for (int t = 0; t < ms_threads_count(); t++)
        for (int k = 0; k < MS_RT_NRAYKINDS; k++) st->rays[k] += f->rays[t][k];
}

/* Pass f->pass over every tile. */
static void one_pass(frame *f, ms_rt_stats *st)
{
    f->passes = 1;
    trace_round(f, 0, frame_tiles(f), st);
    st->passes = f->pass + 1;
}

static void run_passes(frame *f, const ms_rt_options *o, ms_rt_stats *st)
{
    int total = o->aasamples + 1;
    if (o->max_passes > 0 && o->max_passes < total) total = o->max_passes;
    double t0 = ms_now(), c0 = cpu_now();
    char what[64];
    if (o->time_budget > 0 || o->order == MS_RT_ORDER_PASSES) {  /* a budget is checked after each pass */
        for (f->pass = 0; f->pass < total; f->pass++) {
            one_pass(f, st);
            if (o->progress) {
                snprintf(what, sizeof what, "pass %d/%d", st->passes, total);
                progress(st, what, t0);
            }
            if (o->time_budget > 0 && ms_now() - t0 >= o->time_budget) break;
        }
    } else {                    /* pixel after pixel, all passes: in rounds to report or dump */
        size_t ntiles = frame_tiles(f), rounds = 1;
        if (o->progress || f->dump) rounds = MS_MIN(ntiles, (size_t)MS_MAX(16, total));
        f->pass = 0;
        f->passes = total;
        for (size_t r = 0; r < rounds; r++) {
            trace_round(f, ntiles * r / rounds, ntiles * (r + 1) / rounds, st);
            if (o->progress) {
                snprintf(what, sizeof what, "%d%% of %d passes", (int)(100 * (r + 1) / rounds), total);
                progress(st, what, t0);
            }
        }
        f->pass = st->passes = total;
    }
    st->trace_s = ms_now() - t0;
    st->trace_cpu_s = cpu_now() - c0;
}

/* The average of the passes, clamped to [0, 1] and scaled to 8 bits by truncation, as
 * Tachyon does (so equal colours give equal bytes). */
static void to_image(const frame *f, int passes, ms_image *img)
{
    size_t n = 3 * (size_t)f->width * (size_t)f->height;
    float scale = 255.0f / (float)passes;
    for (size_t i = 0; i < n; i++) {
        float v = f->accum[i] * scale;
        img->rgb[i] = (uint8_t)(!(v > 0.0f) ? 0.0f : v > 255.0f ? 255.0f : v);
    }
}

/* The frame's buffers (sh is kept by pointer); 0, or -1 with err set and nothing held. */
static int frame_init(frame *f, const ms_scene *s, const rt_shader *sh, const ms_rt_options *o,
                      ms_error *err)
{
    size_t npix = (size_t)s->width * (size_t)s->height;
    int depth = o->max_depth > 0 && o->max_depth < MS_RT_MAX_DEPTH ? o->max_depth : MS_RT_MAX_DEPTH;
    *f = (frame){sh, s->width, s->height, (s->width + TILE - 1) / TILE, 0, depth, 1, 0, NULL, NULL, NULL, NULL};
    f->accum = ms_calloc_array(3 * npix, sizeof(float));
    f->rng = ms_alloc_array(npix, sizeof(uint32_t));
    f->rays = ms_calloc_array((size_t)ms_threads_count(), sizeof *f->rays);
    if (!f->accum || !f->rng || !f->rays) {
        ms_error_set(err, "out of memory for a %dx%d image", s->width, s->height);
        free(f->accum);
        free(f->rng);
        free(f->rays);
        return -1;
    }
    for (size_t i = 0; i < npix; i++) f->rng[i] = rt_hash2((uint32_t)i, 0x6d2b79f5u);
    return 0;
}

static void frame_free(frame *f)
{
    free(f->accum);
    free(f->rng);
    free(f->rays);
}

/* The last render's memory (ms_rt_last_memory); renders run one at a time. */
static ms_rt_memory last_memory;

void ms_rt_last_memory(ms_rt_memory *out) { *out = last_memory; }

static int trace_frame(const ms_scene *s, const rt_world *w, const ms_rt_options *o, ms_image *img,
                       ms_rt_stats *st, ms_error *err)
{
    frame f;
    rt_shader sh;
    rt_shader_init(&sh, s, w, o->aosamples);
    if (frame_init(&f, s, &sh, o, err)) return -1;
    size_t npix = (size_t)s->width * (size_t)s->height;
    last_memory.world = w->owned_bytes;
    last_memory.frame = npix * (3 * sizeof(float) + sizeof(uint32_t));
    last_memory.image = 3 * npix;
    int rc = ms_image_alloc(img, s->width, s->height, err);
    if (rc == 0 && o->raydump && *o->raydump) {
        f.dump = rt_raydump_open(o->raydump, w, err);
        if (!f.dump) rc = -1;
    }
    if (rc == 0) {
        run_passes(&f, o, st);
        to_image(&f, st->passes, img);
        rc = rt_raydump_close(f.dump, 1, err);
    }
    frame_free(&f);
    return rc;
}

int ms_rt_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                 ms_error *err)
{
    ms_rt_stats local;
    if (!st) st = &local;
    memset(st, 0, sizeof *st);
    memset(img, 0, sizeof *img);
    if (rt_check_options(s, o, err) || rt_plan_memory(s, o, err)) return -1;
    rt_world w;
    size_t held0 = rt_device_held();
    rt_device_peak_reset();
    double t0 = ms_now(), c0 = cpu_now();
    int passes = o->max_passes > 0 && o->max_passes < o->aasamples + 1 ? o->max_passes : o->aasamples + 1;
    double samples = (double)s->width * (double)s->height * passes;
    int rc = rt_world_build(&w, s, samples, samples * rt_rays_per_sample(s, o->aosamples),
                            o->leaves, err);
    st->build_s = ms_now() - t0;
    st->build_cpu_s = cpu_now() - c0;
    if (rc == 0) {
        rc = trace_frame(s, &w, o, img, st, err);
        last_memory.embree = rt_device_peak() - held0;
        rt_world_free(&w);
    }
    rt_device_set_budget(0);
    if (rc) ms_image_free(img);
    return rc;
}

typedef struct rt_write_job {
    const ms_scene *s;
    const ms_rt_options *o;
    ms_rt_stats *st;
} rt_write_job;

static int render_job(void *user, ms_image *img, ms_error *err)
{
    const rt_write_job *j = user;
    return ms_rt_render(j->s, j->o, img, j->st, err);
}

int ms_rt_write(const ms_scene *s, const ms_rt_options *o, const char *path, ms_rt_stats *st,
                ms_error *err)
{
    rt_write_job j = {s, o, st};
    return ms_render_write_image(path, render_job, &j, err);
}

/* ---------------------------------------------------------------- sessions */

struct ms_rt_session {
    rt_world world;
    rt_shader sh;
    frame f;
    ms_rt_stats st;
};

ms_rt_session *ms_rt_session_begin(const ms_scene *s, const ms_rt_options *o, ms_error *err)
{
    if (rt_check_options(s, o, err) || rt_plan_memory(s, o, err)) return NULL;
    ms_rt_session *ss = calloc(1, sizeof *ss);
    if (!ss) {
        ms_error_set(err, "out of memory");
        rt_device_set_budget(0);
        return NULL;
    }
    double t0 = ms_now();
    int rc = rt_world_build(&ss->world, s, 0, 0, o->leaves, err);
    ss->st.build_s = ms_now() - t0;
    rt_device_set_budget(0);
    if (rc) {
        free(ss);
        return NULL;
    }
    rt_shader_init(&ss->sh, s, &ss->world, o->aosamples);
    if (frame_init(&ss->f, s, &ss->sh, o, err)) {
        rt_world_free(&ss->world);
        free(ss);
        return NULL;
    }
    return ss;
}

int ms_rt_session_pass(ms_rt_session *ss)
{
    double t0 = ms_now();
    one_pass(&ss->f, &ss->st);
    ss->f.pass++;
    ss->st.trace_s += ms_now() - t0;
    return ss->f.pass;
}

int ms_rt_session_passes(const ms_rt_session *ss)
{
    return ss->f.pass;
}

int ms_rt_session_image(const ms_rt_session *ss, ms_image *img, ms_error *err)
{
    memset(img, 0, sizeof *img);
    if (ss->f.pass < 1) {
        ms_error_set(err, "no pass has been traced yet");
        return -1;
    }
    if (ms_image_alloc(img, ss->f.width, ss->f.height, err)) return -1;
    to_image(&ss->f, ss->f.pass, img);
    return 0;
}

void ms_rt_session_end(ms_rt_session *ss)
{
    if (!ss) return;
    frame_free(&ss->f);
    rt_world_free(&ss->world);
    free(ss);
}
