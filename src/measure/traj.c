/* traj.c: measurements over the frames of one molecule: average positions and RMS
 * fluctuations. The loop runs over atoms in parallel, each chunk walking all the frames. */
#include "config.h"
#include "measure/internal.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>

int ms_frame_range_make(const ms_molecule *m, long first, long last, long step,
                        ms_frame_range *r, ms_error *err)
{
    long max = (long)m->nframes - 1;
    if (last == -1) last = max;
    if (m->nframes == 0 || first < 0 || first > last || last > max || step <= 0) {
        ms_error_set(err, "frames %ld to %ld step %ld are out of range (molecule %d has %zu "
                     "frames)", first, last, step, m->id, m->nframes);
        return -1;
    }
    r->first = (size_t)first;
    r->last = (size_t)last;
    r->step = (size_t)step;
    return 0;
}

typedef struct traj_ctx {
    const ms_molecule *m;
    const uint32_t *atoms;
    const ms_frame_range *r;
    double *avpos, *rmsf;
} traj_ctx;

static size_t nframes_in(const ms_frame_range *r) { return (r->last - r->first) / r->step + 1; }

static void avpos_range(void *vctx, size_t begin, size_t end, int thread)
{
    traj_ctx *c = vctx;
    double inv = 1.0 / (double)nframes_in(c->r);
    for (size_t i = begin; i < end; i++)
        for (int k = 0; k < 3; k++) c->avpos[3 * i + k] = 0.0;
    for (size_t f = c->r->first; f <= c->r->last; f += c->r->step) {
        const float *pos = c->m->frames[f].pos;
        for (size_t i = begin; i < end; i++)
            for (int k = 0; k < 3; k++) c->avpos[3 * i + k] += pos[3 * (size_t)c->atoms[i] + k];
    }
    for (size_t i = begin; i < end; i++)
        for (int k = 0; k < 3; k++) c->avpos[3 * i + k] *= inv;
}

static void rmsf_range(void *vctx, size_t begin, size_t end, int thread)
{
    traj_ctx *c = vctx;
    avpos_range(vctx, begin, end, thread);
    for (size_t i = begin; i < end; i++) c->rmsf[i] = 0.0;
    for (size_t f = c->r->first; f <= c->r->last; f += c->r->step) {
        const float *pos = c->m->frames[f].pos;
        for (size_t i = begin; i < end; i++)
            for (int k = 0; k < 3; k++) {
                double d = pos[3 * (size_t)c->atoms[i] + k] - c->avpos[3 * i + k];
                c->rmsf[i] += d * d;
            }
    }
    double inv = 1.0 / (double)nframes_in(c->r);
    for (size_t i = begin; i < end; i++) c->rmsf[i] = sqrt(c->rmsf[i] * inv);
}

static int check_range(const ms_molecule *m, const ms_frame_range *r, ms_error *err)
{
    if (r->step == 0 || r->first > r->last || r->last >= m->nframes) {
        ms_error_set(err, "frames %zu to %zu are out of range (molecule %d has %zu frames)",
                     r->first, r->last, m->id, m->nframes);
        return -1;
    }
    return 0;
}

/* A streamed molecule is read frame after frame (each once per pass, into its window), the
 * atoms of each frame in parallel, summing in the same order as the loops above: pass 0
 * sums positions, pass 1 squared deviations from their average. */
typedef struct frame_job {
    const traj_ctx *c;
    const float *pos;
    int pass;
} frame_job;

static void frame_add(void *vctx, size_t begin, size_t end, int thread)
{
    (void)thread;
    const frame_job *j = vctx;
    const traj_ctx *c = j->c;
    for (size_t i = begin; i < end; i++)
        for (int k = 0; k < 3; k++) {
            double p = j->pos[3 * (size_t)c->atoms[i] + k];
            if (j->pass == 0) c->avpos[3 * i + k] += p;
            else c->rmsf[i] += (p - c->avpos[3 * i + k]) * (p - c->avpos[3 * i + k]);
        }
}

static int streamed(const traj_ctx *c, size_t n, int passes, ms_error *err)
{
    double inv = 1.0 / (double)nframes_in(c->r);
    for (size_t i = 0; i < 3 * n; i++) c->avpos[i] = 0.0;
    for (size_t i = 0; c->rmsf && i < n; i++) c->rmsf[i] = 0.0;
    for (int pass = 0; pass < passes; pass++) {
        for (size_t f = c->r->first; f <= c->r->last; f += c->r->step) {
            frame_job j = {c, ms_mol_frame_pos(c->m, f, err), pass};
            if (!j.pos) return -1;
            ms_parallel_for(n, 4096, frame_add, &j);
        }
        if (pass == 0)
            for (size_t i = 0; i < 3 * n; i++) c->avpos[i] *= inv;
    }
    for (size_t i = 0; c->rmsf && i < n; i++) c->rmsf[i] = sqrt(c->rmsf[i] * inv);
    return 0;
}

int ms_measure_avpos(const ms_molecule *m, const uint32_t *atoms, size_t n,
                     const ms_frame_range *r, double *avpos, ms_error *err)
{
    if (check_range(m, r, err)) return -1;
    traj_ctx ctx = {m, atoms, r, avpos, NULL};
    if (m->stream) return streamed(&ctx, n, 1, err);
    ms_parallel_for(n, 4096, avpos_range, &ctx);
    return 0;
}

int ms_measure_rmsf(const ms_molecule *m, const uint32_t *atoms, size_t n,
                    const ms_frame_range *r, double *rmsf, ms_error *err)
{
    if (check_range(m, r, err)) return -1;
    double *avpos = ms_alloc_array(n, 3 * sizeof *avpos);
    if (!avpos) {
        ms_error_set(err, "out of memory for %zu atoms", n);
        return -1;
    }
    traj_ctx ctx = {m, atoms, r, avpos, rmsf};
    int rc = 0;
    if (m->stream) rc = streamed(&ctx, n, 2, err);
    else ms_parallel_for(n, 4096, rmsf_range, &ctx);
    free(avpos);
    return rc;
}
