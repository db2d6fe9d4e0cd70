/* fit.c: optimal superposition (Horn's quaternion method, J. Opt. Soc. Am. A 4, 629 (1987)).
 * The rotation that best maps the centred points x onto the centred points y is the unit
 * quaternion maximising q^T N q, where N is a symmetric 4x4 matrix built from the weighted
 * covariance; that is N's eigenvector of largest eigenvalue. A quaternion is always a proper
 * rotation, so mirror images are fitted by the best rotation, never by a reflection. */
#include "config.h"
#include "measure/internal.h"
#include "vecmath/vecmath.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Weighted centers of x and y; -1 when the weights sum to zero. */
static int centers(size_t n, const double *x, const double *y, const double *w, double cx[3],
                   double cy[3], ms_error *err)
{
    double sw = 0.0;
    for (int k = 0; k < 3; k++) cx[k] = cy[k] = 0.0;
    for (size_t i = 0; i < n; i++) {
        double wi = w ? w[i] : 1.0;
        sw += wi;
        for (int k = 0; k < 3; k++) {
            cx[k] += wi * x[3 * i + k];
            cy[k] += wi * y[3 * i + k];
        }
    }
    if (sw == 0.0 || !isfinite(sw)) {
        ms_error_set(err, "the weights sum to %g, cannot divide by it", sw);
        return -1;
    }
    for (int k = 0; k < 3; k++) cx[k] /= sw, cy[k] /= sw;
    return 0;
}

/* Horn's N from the covariance S[a][b] = sum w (x_a - cx_a)(y_b - cy_b). */
static void horn_matrix(const double S[3][3], double N[16])
{
    double xx = S[0][0], xy = S[0][1], xz = S[0][2], yx = S[1][0], yy = S[1][1], yz = S[1][2],
           zx = S[2][0], zy = S[2][1], zz = S[2][2];
    double n[16] = {xx + yy + zz, yz - zy,       zx - xz,        xy - yx,
                    yz - zy,      xx - yy - zz,  xy + yx,        zx + xz,
                    zx - xz,      xy + yx,       -xx + yy - zz,  yz + zy,
                    xy - yx,      zx + xz,       yz + zy,        -xx - yy + zz};
    memcpy(N, n, sizeof n);
}

/* The rotation matrix of the unit quaternion (q0; q1 q2 q3), into the 3x3 part of m. */
static void quaternion_rotation(const double q[4], double m[16])
{
    double a = q[0], b = q[1], c = q[2], d = q[3];
    double r[9] = {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
                   2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b),
                   2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d};
    ms_mat4d_identity(m);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) m[4 * i + j] = r[3 * i + j];
}

int ms_measure_fit_points(size_t n, const double *x, const double *y, const double *w,
                          double m[16], ms_error *err)
{
    double cx[3], cy[3], S[3][3] = {{0}}, N[16], evals[4], evecs[16];
    if (n == 0) {
        ms_error_set(err, "no atoms in selection");
        return -1;
    }
    if (centers(n, x, y, w, cx, cy, err)) return -1;
    for (size_t i = 0; i < n; i++) {
        double wi = w ? w[i] : 1.0;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                S[a][b] += wi * (x[3 * i + a] - cx[a]) * (y[3 * i + b] - cy[b]);
    }
    horn_matrix(S, N);
    if (ms_eigen_sym(4, N, evals, evecs)) {
        ms_error_set(err, "could not find the best rotation (coordinates not finite?)");
        return -1;
    }
    quaternion_rotation(evecs, m);   /* eigenvector of the largest eigenvalue */
    double rc[3];
    ms_mat4d_point(m, cx, rc);  /* translation: cy - R cx */
    for (int k = 0; k < 3; k++) m[4 * k + 3] = cy[k] - rc[k];
    return 0;
}

/* Copy the coordinates of a set, optionally reordered: out[i] = atom order[i]. */
static void gather(const ms_atomset *s, const uint32_t *order, double *out)
{
    const float *pos = ms_atomset_pos(s);
    for (size_t i = 0; i < s->n; i++)
        ms_pos3(pos, s->atoms[order ? order[i] : i], out + 3 * i);
}

int ms_measure_fit(const ms_atomset *a, const ms_atomset *b, const double *w,
                   const uint32_t *order, double m[16], ms_error *err)
{
    if (ms_atomset_check(a, err) || ms_atomset_check(b, err)) return -1;
    if (a->n != b->n) {
        ms_error_set(err, "selections must have the same number of atoms (%zu and %zu)",
                     a->n, b->n);
        return -1;
    }
    for (size_t i = 0; order && i < a->n; i++)
        if (order[i] >= a->n) {
            ms_error_set(err, "order index %u is out of range (0 to %zu)", order[i], a->n - 1);
            return -1;
        }
    double *x = ms_alloc_array(a->n, 3 * sizeof *x), *y = ms_alloc_array(a->n, 3 * sizeof *y);
    int rc = -1;
    if (!x || !y) ms_error_set(err, "out of memory for %zu atoms", a->n);
    else {
        gather(a, NULL, x);
        gather(b, order, y);
        rc = ms_measure_fit_points(a->n, x, y, w, m, err);
    }
    free(x);
    free(y);
    return rc;
}
