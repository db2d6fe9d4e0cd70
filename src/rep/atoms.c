/* atoms.c: helpers of the atom and bond methods: scratch memory, prefix sums, a sphere per
 * selected atom, the bonds drawn (the molecule's, or by a distance cutoff) and half-bond
 * cylinders. Every fill is claimed as one block and written in parallel. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void *ms_rep_scratch_get(ms_rep_scratch *s, int slot, size_t bytes, ms_error *err)
{
    if (bytes == 0) bytes = 1;
    if (s->cap[slot] < bytes) {
        size_t want = bytes + bytes / 8;
        void *p = realloc(s->buf[slot], want);
        if (!p) {
            ms_error_set(err, "out of memory (%zu bytes of scratch space)", bytes);
            return NULL;
        }
        s->buf[slot] = p;
        s->cap[slot] = want;
    }
    return s->buf[slot];
}

void ms_rep_scratch_free(ms_rep_scratch *s)
{
    for (int k = 0; k < MS_REP_NSCRATCH; k++) free(s->buf[k]);
    memset(s, 0, sizeof *s);
}

size_t ms_rep_scan(size_t *v, size_t n)
{
    size_t acc = 0;
    for (size_t i = 0; i < n; i++) {
        size_t c = v[i];
        v[i] = acc;
        acc += c;
    }
    return acc;
}

/* ---------------------------------------------------------------- spheres */

typedef struct sphere_job {
    const ms_rep_build *b;
    ms_dl_spheres *sp;
    size_t s0;
    float radscale, fixrad;
    uint16_t res;
} sphere_job;

static void fill_spheres(void *ctxp, size_t begin, size_t end, int thread)
{
    const sphere_job *j = ctxp;
    const ms_rep_build *b = j->b;
    const float *radius = b->m->atoms.radius;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = b->idx[s];
        size_t o = j->s0 + s;
        memcpy(j->sp->xyz + 3 * o, ms_rep_xyz(b, i), 3 * sizeof(float));
        j->sp->radius[o] = radius[i] * j->radscale + j->fixrad;
        j->sp->color[o] = ms_rep_rgba(b, i);
        j->sp->res[o] = j->res;
    }
}

int ms_rep_atom_spheres(const ms_rep_build *b, float radscale, float fixrad, int res,
                        ms_displaylist *dl, ms_error *err)
{
    if (!(radscale + fixrad > 0) || b->nsel == 0) return 0;
    long s0 = ms_dl_extend(dl, MS_DL_SPHERES, b->nsel, err);
    if (s0 < 0) return -1;
    sphere_job j = {b, &dl->spheres, (size_t)s0, radscale, fixrad, (uint16_t)res};
    ms_parallel_for(b->nsel, 16384, fill_spheres, &j);
    return 0;
}

/* ---------------------------------------------------------------- bonds */

int ms_rep_may_bond(const ms_molecule *m, uint32_t i, uint32_t j)
{
    const ms_atoms *a = &m->atoms;
    if ((a->flags[i] & MS_AF_HYDROGEN) && (a->flags[j] & MS_AF_HYDROGEN)) return 0;
    return !(a->altloc[i] != a->altloc[j] && a->altloc[i] && a->altloc[j]);
}

static int keep_bond(const void *ctx, uint32_t i, uint32_t j)
{
    return ms_rep_may_bond(ctx, i, j);
}

int ms_rep_bonds_get(const ms_rep_build *b, float cutoff, ms_rep_bondlist *out, ms_error *err)
{
    const ms_molecule *m = b->m;
    size_t n = m->atoms.n;
    if (!(cutoff > 0) && m->has_bonds) {
        out->start = m->bonds.start;
        out->to = m->bonds.to;
        return 0;
    }
    uint32_t *pairs = NULL;
    size_t np = 0;
    if (cutoff > 0 && ms_rep_pairs(b, cutoff, keep_bond, m, &pairs, &np, err)) return -1;
    uint32_t *start = ms_rep_scratch_get(b->scratch, MS_SCR_BONDSTART, (n + 1) * sizeof *start, err);
    uint32_t *to = ms_rep_scratch_get(b->scratch, MS_SCR_BONDTO, (2 * np + 1) * sizeof *to, err);
    if (!start || !to) return -1;
    memset(start, 0, (n + 1) * sizeof *start);
    for (size_t k = 0; k < 2 * np; k++) start[pairs[k] + 1]++;
    for (size_t i = 0; i < n; i++) start[i + 1] += start[i];
    for (size_t k = 0; k < np; k++) {   /* start[i] walks forward, then is restored */
        to[start[pairs[2 * k]]++] = pairs[2 * k + 1];
        to[start[pairs[2 * k + 1]]++] = pairs[2 * k];
    }
    for (size_t i = n; i > 0; i--) start[i] = start[i - 1];
    start[0] = 0;
    out->start = start;
    out->to = to;
    return 0;
}

/* ---------------------------------------------------------------- half-bond cylinders */

typedef struct half_job {
    const ms_rep_build *b;
    const ms_rep_bondlist *bl;
    ms_dl_cylinders *cy;
    size_t *first;              /* per selected position: its first cylinder */
    size_t c0;
    float radius;
    uint16_t res;
} half_job;

static void count_half(void *ctxp, size_t begin, size_t end, int thread)
{
    const half_job *j = ctxp;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = j->b->idx[s];
        size_t c = 0;
        for (uint32_t k = j->bl->start[i]; k < j->bl->start[i + 1]; k++)
            c += (size_t)ms_rep_on(j->b, j->bl->to[k]);
        j->first[s] = c;
    }
}

static void fill_half(void *ctxp, size_t begin, size_t end, int thread)
{
    const half_job *j = ctxp;
    const ms_rep_build *b = j->b;
    ms_dl_cylinders *cy = j->cy;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = b->idx[s];
        size_t c = j->c0 + j->first[s];
        const float *p = ms_rep_xyz(b, i);
        ms_rgba8 col = ms_rep_rgba(b, i);
        for (uint32_t k = j->bl->start[i]; k < j->bl->start[i + 1]; k++) {
            uint32_t o = j->bl->to[k];
            if (!ms_rep_on(b, o)) continue;
            const float *q = ms_rep_xyz(b, o);
            float *base = cy->base + 3 * c, *apex = cy->apex + 3 * c;
            for (int d = 0; d < 3; d++) {
                base[d] = p[d];
                apex[d] = 0.5f * (p[d] + q[d]);
            }
            cy->radius[c] = j->radius;
            cy->color[c] = col;
            cy->caps[c] = 0;
            cy->res[c] = j->res;
            c++;
        }
    }
}

int ms_rep_half_cylinders(const ms_rep_build *b, const ms_rep_bondlist *bl, float radius, int res,
                          ms_displaylist *dl, ms_error *err)
{
    if (b->nsel == 0) return 0;
    half_job j = {b, bl, &dl->cylinders, NULL, 0, radius, (uint16_t)res};
    j.first = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (b->nsel + 1) * sizeof(size_t), err);
    if (!j.first) return -1;
    ms_parallel_for(b->nsel, 16384, count_half, &j);
    size_t total = ms_rep_scan(j.first, b->nsel);
    long c0 = ms_dl_extend(dl, MS_DL_CYLINDERS, total, err);
    if (c0 < 0) return -1;
    j.c0 = (size_t)c0;
    j.cy = &dl->cylinders;
    ms_parallel_for(b->nsel, 16384, fill_half, &j);
    return 0;
}

/* ---------------------------------------------------------------- joints */

/* VMD's gap-free joint: move start back (end forward) by r tan(angle / 2) to meet the
 * cylinder from prev (to next). */
void ms_rep_stretch(const float *prev, const float *start, const float *end,
                    const float *next, float r, float *s, float *e)
{
    float dir[3], l = 0;
    for (int k = 0; k < 3; k++) {
        dir[k] = end[k] - start[k];
        l += dir[k] * dir[k];
    }
    l = sqrtf(l);
    for (int k = 0; k < 3; k++) dir[k] = l > 0 ? dir[k] / l : 0;
    float ls = 0, le = 0;
    for (int pass = 0; pass < 2; pass++) {
        const float *a = pass ? end : prev, *b = pass ? next : start;
        if (!a || !b) continue;
        float o[3], ol = 0, c = 0;
        for (int k = 0; k < 3; k++) {
            o[k] = b[k] - a[k];
            ol += o[k] * o[k];
        }
        ol = sqrtf(ol);
        if (!(ol > 0)) continue;
        for (int k = 0; k < 3; k++) c += o[k] / ol * dir[k];
        if (c > 0.0f && c < 0.9999f) *(pass ? &le : &ls) = r * sqrtf((1 - c) / (1 + c));
    }
    for (int k = 0; k < 3; k++) {
        s[k] = start[k] - ls * dir[k];
        e[k] = end[k] + le * dir[k];
    }
}
