/* volume.c: volumetric data sets of a molecule: statistics, interpolation, the list. */
#include "config.h"
#include "molecule/volume.h"
#include "molecule/molecule.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

size_t ms_volume_size(const ms_volume *v)
{
    if (v->n[0] <= 0 || v->n[1] <= 0 || v->n[2] <= 0) return 0;
    return (size_t)v->n[0] * (size_t)v->n[1] * (size_t)v->n[2];
}

void ms_volume_clear(ms_volume *v)
{
    free(v->name);
    free(v->data);
    memset(v, 0, sizeof *v);
}

#define STAT_THREADS 256

typedef struct stat_ctx {
    const float *data;
    double sum[STAT_THREADS], sum2[STAT_THREADS];
    float lo[STAT_THREADS], hi[STAT_THREADS];
    int used[STAT_THREADS];
    double mean;
} stat_ctx;

static void stat_range(void *ctx, size_t b, size_t e, int t)
{
    stat_ctx *c = ctx;
    if (t >= STAT_THREADS) t = STAT_THREADS - 1;
    double s = 0, s2 = 0;
    float lo = c->used[t] ? c->lo[t] : c->data[b], hi = c->used[t] ? c->hi[t] : c->data[b];
    for (size_t i = b; i < e; i++) {
        float v = c->data[i];
        double d = (double)v - c->mean;
        s += v;
        s2 += d * d;
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    c->sum[t] += s;
    c->sum2[t] += s2;
    c->lo[t] = lo;
    c->hi[t] = hi;
    c->used[t] = 1;
}

/* Two passes: the mean first, then deviations from it (no cancellation). */
void ms_volume_stats(ms_volume *v)
{
    size_t n = ms_volume_size(v);
    v->min = v->max = v->mean = v->sigma = 0.0f;
    if (n == 0 || !v->data) return;
    stat_ctx *c = calloc(1, sizeof *c);
    if (!c) return;
    c->data = v->data;
    ms_parallel_for(n, 1 << 16, stat_range, c);
    double sum = 0;
    float lo = v->data[0], hi = v->data[0];
    for (int t = 0; t < STAT_THREADS; t++) {
        if (!c->used[t]) continue;
        sum += c->sum[t];
        lo = c->lo[t] < lo ? c->lo[t] : lo;
        hi = c->hi[t] > hi ? c->hi[t] : hi;
    }
    c->mean = sum / (double)n;
    memset(c->sum2, 0, sizeof c->sum2);
    memset(c->used, 0, sizeof c->used);
    ms_parallel_for(n, 1 << 16, stat_range, c);
    double s2 = 0;
    for (int t = 0; t < STAT_THREADS; t++) s2 += c->sum2[t];
    v->min = lo;
    v->max = hi;
    v->mean = (float)c->mean;
    v->sigma = (float)sqrt(s2 / (double)n);
    free(c);
}

int ms_volume_grid_coords(const ms_volume *v, const float p[3], double g[3])
{
    /* Solve p - origin = D g, D's columns the step vectors (Cramer's rule). */
    const float (*d)[3] = v->delta;
    double a[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = d[c][r];
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (!(fabs(det) > 1e-30)) return -1;
    double b[3] = {(double)p[0] - v->origin[0], (double)p[1] - v->origin[1],
                   (double)p[2] - v->origin[2]};
    for (int k = 0; k < 3; k++) {
        double m[3][3];
        memcpy(m, a, sizeof m);
        for (int r = 0; r < 3; r++) m[r][k] = b[r];
        g[k] = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) / det;
    }
    return 0;
}

/* Trilinear interpolation at grid coordinates already inside 0 .. n - 1. */
static float interpolate(const ms_volume *v, const double g[3])
{
    int i0[3];
    double f[3];
    for (int k = 0; k < 3; k++) {
        i0[k] = (int)g[k];
        if (i0[k] >= v->n[k] - 1) i0[k] = v->n[k] > 1 ? v->n[k] - 2 : 0;
        f[k] = g[k] - i0[k];
    }
    size_t sx = 1, sy = (size_t)v->n[0], sz = sy * (size_t)v->n[1];
    size_t step[3] = {v->n[0] > 1 ? sx : 0, v->n[1] > 1 ? sy : 0, v->n[2] > 1 ? sz : 0};
    size_t base = (size_t)i0[0] * sx + (size_t)i0[1] * sy + (size_t)i0[2] * sz;
    double r = 0;
    for (int c = 0; c < 8; c++) {
        double w = 1;
        size_t off = base;
        for (int k = 0; k < 3; k++) {
            int bit = (c >> k) & 1;
            w *= bit ? f[k] : 1.0 - f[k];
            off += bit ? step[k] : 0;
        }
        if (w != 0) r += w * v->data[off];
    }
    return (float)r;
}

float ms_volume_value(const ms_volume *v, const float p[3], float outside)
{
    double g[3];
    if (!v->data || ms_volume_size(v) == 0 || ms_volume_grid_coords(v, p, g)) return outside;
    for (int k = 0; k < 3; k++)
        if (!(g[k] >= 0.0 && g[k] <= (double)(v->n[k] - 1))) return outside;
    return interpolate(v, g);
}

float ms_volume_value_at(const ms_volume *v, const double g[3])
{
    if (!v->data || ms_volume_size(v) == 0) return 0.0f;
    double c[3];
    for (int k = 0; k < 3; k++) {
        double hi = (double)(v->n[k] - 1);
        c[k] = g[k] > 0.0 ? (g[k] < hi ? g[k] : hi) : 0.0;   /* NaN goes to 0 */
    }
    return interpolate(v, c);
}

void ms_volume_point(const ms_volume *v, const double g[3], float p[3])
{
    for (int r = 0; r < 3; r++)
        p[r] = (float)(v->origin[r] + g[0] * v->delta[0][r] + g[1] * v->delta[1][r] +
                       g[2] * v->delta[2][r]);
}

void ms_volume_bounds(const ms_volume *v, float lo[3], float hi[3])
{
    for (int c = 0; c < 8; c++) {
        double g[3];
        float p[3];
        for (int k = 0; k < 3; k++) g[k] = (c >> k & 1) ? (double)MS_MAX(v->n[k] - 1, 0) : 0.0;
        ms_volume_point(v, g, p);
        for (int k = 0; k < 3; k++) {
            lo[k] = c == 0 || p[k] < lo[k] ? p[k] : lo[k];
            hi[k] = c == 0 || p[k] > hi[k] ? p[k] : hi[k];
        }
    }
}

void ms_volume_sampler_init(ms_volume_sampler *s, const ms_volume *v)
{
    memset(s, 0, sizeof *s);
    s->v = v;
    double a[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = v->delta[c][r];
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (!v->data || ms_volume_size(v) == 0 || !(fabs(det) > 1e-30)) return;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            /* inverse[c][r] = cofactor of a[r][c] / det */
            s->inv[c][r] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
        }
    s->ok = 1;
}

float ms_volume_sample(const ms_volume_sampler *s, const float p[3])
{
    if (!s->ok) return 0.0f;
    const ms_volume *v = s->v;
    double d[3] = {(double)p[0] - v->origin[0], (double)p[1] - v->origin[1],
                   (double)p[2] - v->origin[2]};
    double g[3];
    for (int k = 0; k < 3; k++) g[k] = s->inv[k][0] * d[0] + s->inv[k][1] * d[1] + s->inv[k][2] * d[2];
    return ms_volume_value_at(v, g);
}

long ms_mol_add_volume(ms_molecule *m, ms_volume *v, ms_error *err)
{
    size_t cap = m->nvolumes;
    ms_volume *nv = realloc(m->volumes, (cap + 1) * sizeof *nv);
    if (!nv) {
        ms_volume_clear(v);
        ms_error_set(err, "out of memory for a volume");
        return -1;
    }
    m->volumes = nv;
    ms_volume_stats(v);
    m->volumes[m->nvolumes] = *v;
    memset(v, 0, sizeof *v);
    return (long)m->nvolumes++;
}

int ms_mol_delete_volume(ms_molecule *m, size_t k)
{
    if (k >= m->nvolumes) return -1;
    ms_volume_clear(&m->volumes[k]);
    memmove(m->volumes + k, m->volumes + k + 1, (m->nvolumes - k - 1) * sizeof *m->volumes);
    m->nvolumes--;
    return 0;
}

void ms_mol_free_volumes(ms_molecule *m)
{
    for (size_t k = 0; k < m->nvolumes; k++) ms_volume_clear(&m->volumes[k]);
    free(m->volumes);
    m->volumes = NULL;
    m->nvolumes = 0;
}
