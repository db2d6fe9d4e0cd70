/* basic.c: measurements over one frame of a set of atoms: weighted center, bounding box,
 * radius of gyration, RMSD between two sets and the inertia tensor. The sums run in parallel
 * over fixed chunks and are combined in order, so results do not depend on the thread
 * schedule. */
#include "config.h"
#include "measure/internal.h"
#include "vecmath/vecmath.h"

#include <math.h>
#include <stdlib.h>

typedef struct set_ctx {
    const ms_atomset *s, *t;   /* t: the second set (rmsd) */
    const float *pos, *pos2;
    const double *w;
    double c[3];               /* a center computed beforehand */
} set_ctx;

/* Sum the chunk accumulators: out[k] = sum over chunks. */
static int reduce_sum(size_t n, size_t k, ms_chunk_fn fn, set_ctx *ctx, double *out,
                      ms_error *err)
{
    size_t nc;
    double *acc = ms_measure_chunks(n, k, fn, ctx, &nc);
    if (!acc) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (size_t j = 0; j < k; j++) out[j] = 0.0;
    for (size_t c = 0; c < nc; c++)
        for (size_t j = 0; j < k; j++) out[j] += acc[c * k + j];
    free(acc);
    return 0;
}

static int check_set(const ms_atomset *s, ms_error *err)
{
    if (ms_atomset_check(s, err)) return -1;
    if (s->n == 0) {
        ms_error_set(err, "no atoms in selection");
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- center */

static void center_chunk(void *vctx, size_t begin, size_t end, double *acc)
{
    set_ctx *c = vctx;
    for (size_t i = begin; i < end; i++) {
        const float *p = c->pos + 3 * (size_t)c->s->atoms[i];
        double w = c->w ? c->w[i] : 1.0;
        acc[0] += w;
        acc[1] += w * p[0];
        acc[2] += w * p[1];
        acc[3] += w * p[2];
    }
}

int ms_measure_center(const ms_atomset *s, const double *w, double c[3], ms_error *err)
{
    if (check_set(s, err)) return -1;
    set_ctx ctx = {.s = s, .pos = ms_atomset_pos(s), .w = w};
    double sum[4];
    if (reduce_sum(s->n, 4, center_chunk, &ctx, sum, err)) return -1;
    if (sum[0] == 0.0 || !isfinite(sum[0])) {
        ms_error_set(err, "the weights sum to %g, cannot divide by it", sum[0]);
        return -1;
    }
    for (int k = 0; k < 3; k++) c[k] = sum[k + 1] / sum[0];
    return 0;
}

/* ---------------------------------------------------------------- minmax */

typedef struct box_ctx {
    const ms_atomset *s;
    const float *pos;
    int radii;
} box_ctx;

static void box_chunk(void *vctx, size_t begin, size_t end, double *acc)
{
    box_ctx *b = vctx;
    for (int k = 0; k < 3; k++) acc[k] = INFINITY, acc[k + 3] = -INFINITY;
    for (size_t i = begin; i < end; i++) {
        uint32_t a = b->s->atoms[i];
        const float *p = b->pos + 3 * (size_t)a;
        double r = b->radii ? b->s->mol->atoms.radius[a] : 0.0;
        for (int k = 0; k < 3; k++) {
            if (p[k] - r < acc[k]) acc[k] = p[k] - r;
            if (p[k] + r > acc[k + 3]) acc[k + 3] = p[k] + r;
        }
    }
}

int ms_measure_minmax(const ms_atomset *s, int with_radii, double lo[3], double hi[3],
                      ms_error *err)
{
    if (check_set(s, err)) return -1;
    box_ctx ctx = {s, ms_atomset_pos(s), with_radii};
    size_t nc;
    double *acc = ms_measure_chunks(s->n, 6, box_chunk, &ctx, &nc);
    if (!acc) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t c = 0; c < nc; c++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], acc[6 * c + k]);
            hi[k] = fmax(hi[k], acc[6 * c + k + 3]);
        }
    free(acc);
    return 0;
}

/* ---------------------------------------------------------------- rgyr, rmsd */

static void spread_chunk(void *vctx, size_t begin, size_t end, double *acc)
{
    set_ctx *c = vctx;
    for (size_t i = begin; i < end; i++) {
        double p[3], d[3], w = c->w ? c->w[i] : 1.0;
        ms_pos3(c->pos, c->s->atoms[i], p);
        ms_v3_sub(p, c->c, d);
        acc[0] += w;
        acc[1] += w * ms_v3_dot(d, d);
    }
}

int ms_measure_rgyr(const ms_atomset *s, const double *w, double *rgyr, ms_error *err)
{
    set_ctx ctx = {.s = s, .w = w};
    double sum[2];
    if (ms_measure_center(s, w, ctx.c, err)) return -1;
    ctx.pos = ms_atomset_pos(s);
    if (reduce_sum(s->n, 2, spread_chunk, &ctx, sum, err)) return -1;
    *rgyr = sqrt(fmax(sum[1] / sum[0], 0.0));
    return 0;
}

static void rmsd_chunk(void *vctx, size_t begin, size_t end, double *acc)
{
    set_ctx *c = vctx;
    for (size_t i = begin; i < end; i++) {
        double w = c->w ? c->w[i] : 1.0;
        acc[0] += w;
        acc[1] += w * ms_dist2f(c->pos + 3 * (size_t)c->s->atoms[i],
                                c->pos2 + 3 * (size_t)c->t->atoms[i]);
    }
}

int ms_measure_rmsd(const ms_atomset *a, const ms_atomset *b, const double *w, double *rmsd,
                    ms_error *err)
{
    if (check_set(a, err) || check_set(b, err)) return -1;
    if (a->n != b->n) {
        ms_error_set(err, "selections must have the same number of atoms (%zu and %zu)",
                     a->n, b->n);
        return -1;
    }
    set_ctx ctx = {.s = a, .t = b, .pos = ms_atomset_pos(a), .pos2 = ms_atomset_pos(b), .w = w};
    double sum[2];
    if (reduce_sum(a->n, 2, rmsd_chunk, &ctx, sum, err)) return -1;
    if (sum[0] == 0.0 || !isfinite(sum[0])) {
        ms_error_set(err, "the weights sum to %g, cannot divide by it", sum[0]);
        return -1;
    }
    *rmsd = sqrt(fmax(sum[1] / sum[0], 0.0));
    return 0;
}

/* ---------------------------------------------------------------- inertia */

static void tensor_chunk(void *vctx, size_t begin, size_t end, double *acc)
{
    set_ctx *c = vctx;
    for (size_t i = begin; i < end; i++) {
        double p[3], d[3], m = c->w[i];
        ms_pos3(c->pos, c->s->atoms[i], p);
        ms_v3_sub(p, c->c, d);
        acc[0] += m * (d[1] * d[1] + d[2] * d[2]);
        acc[1] += m * (d[0] * d[0] + d[2] * d[2]);
        acc[2] += m * (d[0] * d[0] + d[1] * d[1]);
        acc[3] -= m * d[0] * d[1];
        acc[4] -= m * d[0] * d[2];
        acc[5] -= m * d[1] * d[2];
    }
}

int ms_measure_inertia(const ms_atomset *s, ms_inertia *out, ms_error *err)
{
    if (check_set(s, err)) return -1;
    double *mass = ms_alloc_array(s->n, sizeof *mass), t[6];
    if (!mass) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    set_ctx ctx = {.s = s, .pos = ms_atomset_pos(s), .w = mass};
    int rc = ms_measure_atom_values(s, "mass", mass, err);
    if (!rc && ms_measure_center(s, mass, ctx.c, err)) {
        ms_error_prefix(err, "center of mass");
        rc = -1;
    }
    if (!rc) rc = reduce_sum(s->n, 6, tensor_chunk, &ctx, t, err);
    free(mass);
    if (rc) return -1;
    double tensor[9] = {t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2]}, vec[9];
    if (ms_eigen_sym(3, tensor, out->moments, vec)) {
        ms_error_set(err, "could not diagonalise the inertia tensor");
        return -1;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            out->com[i] = ctx.c[i];
            out->tensor[i][j] = tensor[3 * i + j];
            out->axes[i][j] = vec[3 * i + j];
        }
    return 0;
}
