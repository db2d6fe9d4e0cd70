/* merge.c: VMD's bonds are drawn as two half cylinders, each coloured by its atom, meeting
 * at the bond's midpoint. Two list neighbours that are such a pair (same radius, no caps, the
 * same end point, which is exactly the midpoint of the other two) are one cylinder from atom
 * to atom with a colour for each half: half the primitives for the GL front end, which is
 * what a Licorice view of a million atoms spends its time on under llvmpipe. The surface is
 * the same; the shader picks the colour by the side of the midpoint. */
#include "config.h"
#include "gl/glrender.h"
#include "base/threads.h"

#include <stdlib.h>
#include <string.h>

#define CHUNK 16384

static int same3(const float *a, const float *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* Cylinders i and i + 1 are the halves of one bond. */
static int is_pair(const ms_dl_cylinders *c, size_t i)
{
    const float *a = c->base + 3 * i, *b = c->base + 3 * i + 3, *m = c->apex + 3 * i;
    if (c->caps[i] || c->caps[i + 1] || c->radius[i] != c->radius[i + 1] || !same3(m, m + 3))
        return 0;
    for (int k = 0; k < 3; k++)
        if (m[k] != 0.5f * (a[k] + b[k])) return 0;
    return 1;
}

typedef struct job {
    const ms_dl_cylinders *in;
    uint8_t *flag;
} job;

static void find_pairs(void *ctx, size_t b, size_t e, int t)
{
    job *j = ctx;
    for (size_t i = b; i < e; i++) j->flag[i] = i + 1 < j->in->n && is_pair(j->in, i);
}

/* Left to right, a pair claims both its halves: flag 1 starts a merged pair, 2 is its second
 * half, 0 stays alone. Returns the number of cylinders left. */
static size_t resolve(uint8_t *flag, size_t n)
{
    size_t out = 0;
    for (size_t i = 0; i < n; i++, out++) {
        if (flag[i] == 1) {
            flag[++i] = 2;
            continue;
        }
        flag[i] = 0;
    }
    return out;
}

static void emit(const ms_dl_cylinders *in, const uint8_t *flag, ms_glmerge *m)
{
    ms_dl_cylinders *o = &m->dl.cylinders;
    size_t k = 0;
    for (size_t i = 0; i < in->n; i++, k++) {
        memcpy(o->base + 3 * k, in->base + 3 * i, 3 * sizeof(float));
        o->radius[k] = in->radius[i];
        o->color[k] = m->color2[k] = in->color[i];
        o->caps[k] = in->caps[i];
        if (flag[i] != 1) {
            memcpy(o->apex + 3 * k, in->apex + 3 * i, 3 * sizeof(float));
            continue;
        }
        memcpy(o->apex + 3 * k, in->base + 3 * (i + 1), 3 * sizeof(float));
        m->color2[k] = in->color[i + 1];
        i++;
    }
}

int ms_glmerge_cylinders(const ms_dl_cylinders *in, ms_glmerge *m, ms_error *err)
{
    memset(m, 0, sizeof *m);
    ms_dl_init(&m->dl);
    if (in->n < 2) return 1;
    job j = {in, malloc(in->n)};
    if (!j.flag) goto oom;
    ms_parallel_for(in->n, CHUNK, find_pairs, &j);
    size_t n = resolve(j.flag, in->n);
    if (n > in->n - in->n / 4) {        /* under a quarter merged: not worth the copy */
        free(j.flag);
        return 1;
    }
    ms_dl_cylinders *o = &m->dl.cylinders;
    o->base = ms_alloc_array(3 * n, sizeof(float));
    o->apex = ms_alloc_array(3 * n, sizeof(float));
    o->radius = ms_alloc_array(n, sizeof(float));
    o->color = ms_alloc_array(n, sizeof(ms_rgba8));
    o->caps = malloc(n);
    m->color2 = ms_alloc_array(n, sizeof(ms_rgba8));
    if (!o->base || !o->apex || !o->radius || !o->color || !o->caps || !m->color2) goto oom;
    o->n = o->cap = n;
    emit(in, j.flag, m);
    free(j.flag);
    return 0;
oom:
    free(j.flag);
    ms_glmerge_free(m);
    ms_error_set(err, "out of memory");
    return -1;
}

void ms_glmerge_free(ms_glmerge *m)
{
    ms_dl_cylinders *o = &m->dl.cylinders;
    free(o->base);
    free(o->apex);
    free(o->radius);
    free(o->color);
    free(o->caps);
    free(m->color2);
    memset(m, 0, sizeof *m);
}
