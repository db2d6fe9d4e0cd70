/* frames.c: VMD's drawframes specs ("now", "0:9", "0:2:", "3,5,7") and trajectory smoothing
 * (smoothrep: the coordinates of a frame averaged over a centred window, clamped at the
 * ends, periodic jumps undone for orthogonal cells). */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---------------------------------------------------------------- drawframes */

typedef struct frame_list {
    long *v;
    size_t n, cap;
} frame_list;

static int push(frame_list *l, long f)
{
    if (ms_grow((void **)&l->v, &l->cap, l->n + 1, sizeof *l->v)) return -1;
    l->v[l->n++] = f;
    return 0;
}

/* An integer field of an item (clamped to +-1e9); an empty field takes `empty` (LONG_MIN: not
 * allowed). */
static int field(const char *s, size_t len, long empty, long *out)
{
    if (len == 0) {
        if (empty == LONG_MIN) return -1;
        *out = empty;
        return 0;
    }
    char buf[32];
    if (len >= sizeof buf) return -1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *end;
    long v = strtol(buf, &end, 10);
    /* frames past a billion are never there; the bound keeps the arithmetic below safe */
    *out = v < -1000000000L ? -1000000000L : v > 1000000000L ? 1000000000L : v;
    return *end ? -1 : 0;
}

/* One whitespace-free item into l (l NULL: only check). nframes bounds the ranges walked. */
static int item(const char *s, size_t len, long nframes, long current, frame_list *l)
{
    long last = nframes - 1, a, step = 1, b;
    if (len == 3 && !strncasecmp(s, "now", 3)) return l && current >= 0 ? push(l, current) : 0;
    const char *comma = memchr(s, ',', len);
    if (comma) {
        for (const char *p = s; p <= s + len;) {
            const char *e = memchr(p, ',', (size_t)(s + len - p));
            if (!e) e = s + len;
            if (field(p, (size_t)(e - p), LONG_MIN, &a)) return -1;
            if (l && a >= 0 && a <= last && push(l, a)) return -2;
            p = e + 1;
        }
        return 0;
    }
    const char *c1 = memchr(s, ':', len), *c2 = c1 ? memchr(c1 + 1, ':', (size_t)(s + len - c1 - 1)) : NULL;
    if (!c1) {
        if (field(s, len, LONG_MIN, &a)) return -1;
        return l && a >= 0 && a <= last ? push(l, a) : 0;
    }
    if (field(s, (size_t)(c1 - s), LONG_MIN, &a)) return -1;
    if (c2) {   /* a:step:b, step in the middle */
        if (field(c1 + 1, (size_t)(c2 - c1 - 1), LONG_MIN, &step) || step < 1 ||
            field(c2 + 1, (size_t)(s + len - c2 - 1), last, &b))
            return -1;
    } else if (field(c1 + 1, (size_t)(s + len - c1 - 1), last, &b)) {
        return -1;
    }
    if (!l) return 0;
    if (a < 0) a += ((-a + step - 1) / step) * step;   /* first step inside the frames */
    for (long f = a; f <= b && f <= last; f += step)
        if (push(l, f)) return -2;
    return 0;
}

static int walk(const char *spec, long nframes, long current, frame_list *l, ms_error *err)
{
    int any = 0;
    for (const char *p = spec; *p;) {
        while (*p && isspace((unsigned char)*p)) p++;
        if (!*p) break;
        size_t len = 0;
        while (p[len] && !isspace((unsigned char)p[len])) len++;
        int rc = item(p, len, nframes, current, l);
        if (rc == -1) {
            ms_error_set(err, "bad frame item '%.*s': expected N, a:b, a:step:b, N,M,... or now",
                         (int)len, p);
            return -1;
        }
        if (rc == -2) {
            ms_error_set(err, "out of memory listing frames");
            return -1;
        }
        any = 1;
        p += len;
    }
    if (!any) {
        ms_error_set(err, "empty frame specification");
        return -1;
    }
    return 0;
}

int ms_rep_frames_check(const char *spec, ms_error *err)
{
    return walk(spec, 0, -1, NULL, err);
}

int ms_rep_frames_list(const char *spec, long nframes, long current, long **out, size_t *n,
                       ms_error *err)
{
    frame_list l = {NULL, 0, 0};
    *out = NULL;
    *n = 0;
    if (walk(spec, nframes, current, &l, err)) {
        free(l.v);
        return -1;
    }
    *out = l.v;
    *n = l.n;
    return 0;
}

/* ---------------------------------------------------------------- smoothing */

typedef struct smooth_job {
    const ms_molecule *m;
    long f, half;
    float *out;
} smooth_job;

/* An orthogonal cell with sides, for undoing periodic jumps (VMD handles no other). */
static int ortho_cell(const ms_frame *fr, float box[3])
{
    const float *c = fr->cell;
    if (fabsf(c[0] * c[1] * c[2]) < 1e-4f || c[3] != 90.0f || c[4] != 90.0f || c[5] != 90.0f)
        return 0;
    memcpy(box, c, 3 * sizeof(float));
    return 1;
}

static void smooth_range(void *ctxp, size_t begin, size_t end, int thread)
{
    const smooth_job *j = ctxp;
    const ms_molecule *m = j->m;
    long last = (long)m->nframes - 1;
    const float *ref = m->frames[j->f].pos;
    float scale = 1.0f / (float)(2 * j->half + 1);
    for (size_t k = 3 * begin; k < 3 * end; k++) j->out[k] = 0.0f;
    for (long w = j->f - j->half; w <= j->f + j->half; w++) {
        long fi = w < 0 ? 0 : w > last ? last : w;
        const ms_frame *fr = &m->frames[fi];
        float box[3];
        int pbc = ortho_cell(fr, box);
        for (size_t k = 3 * begin; k < 3 * end; k++) {
            float x = fr->pos[k];
            if (pbc) {
                float b = box[k % 3], d = x - ref[k];
                x += d < -0.5f * b ? b : d > 0.5f * b ? -b : 0.0f;
            }
            j->out[k] += x;
        }
    }
    for (size_t k = 3 * begin; k < 3 * end; k++) j->out[k] *= scale;
}

void ms_rep_smooth(const ms_molecule *m, long f, int half, float *out)
{
    smooth_job j = {m, f, half, out};
    ms_parallel_for(m->atoms.n, 16384, smooth_range, &j);
}
