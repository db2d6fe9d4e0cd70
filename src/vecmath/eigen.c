/* eigen.c: eigenvalues and eigenvectors of small symmetric matrices by cyclic Jacobi
 * rotations (each rotation zeroes one off-diagonal element; sweeps repeat until the
 * off-diagonal part vanishes). Used for the optimal-superposition quaternion (4x4) and the
 * inertia tensor (3x3). */
#include "config.h"
#include "vecmath/vecmath.h"

#include <math.h>
#include <string.h>

#define MAX_SWEEPS 64

/* Off-diagonal and total sums of squares. */
static void norms(int n, const double *a, double *off, double *all)
{
    *off = *all = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double v = a[i * n + j] * a[i * n + j];
            *all += v;
            if (i != j) *off += v;
        }
}

/* Apply the rotation in the (p, q) plane that zeroes a[p][q]: a = J^T a J, v = v J. */
static void rotate(int n, double *a, double *v, int p, int q)
{
    double apq = a[p * n + q];
    double theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
    double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
    double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
    for (int k = 0; k < n; k++) {           /* columns p and q */
        double kp = a[k * n + p], kq = a[k * n + q];
        a[k * n + p] = c * kp - s * kq;
        a[k * n + q] = s * kp + c * kq;
        kp = v[k * n + p], kq = v[k * n + q];
        v[k * n + p] = c * kp - s * kq;
        v[k * n + q] = s * kp + c * kq;
    }
    for (int k = 0; k < n; k++) {           /* rows p and q */
        double pk = a[p * n + k], qk = a[q * n + k];
        a[p * n + k] = c * pk - s * qk;
        a[q * n + k] = s * pk + c * qk;
    }
    a[p * n + q] = a[q * n + p] = 0.0;
}

/* Eigenvalue order, decreasing; equal values keep their original order. */
static void sort_desc(int n, const double *d, int *order)
{
    for (int i = 0; i < n; i++) order[i] = i;
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && d[order[j]] > d[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
}

int ms_eigen_sym(int n, const double *in, double *evals, double *evecs)
{
    double a[16], v[16], off, all;
    if (n < 1 || n > 4) return -1;
    for (int k = 0; k < n * n; k++) {
        if (!isfinite(in[k])) return -1;
        a[k] = in[k];
        v[k] = (k / n == k % n) ? 1.0 : 0.0;
    }
    int sweep;
    for (sweep = 0; sweep < MAX_SWEEPS; sweep++) {
        norms(n, a, &off, &all);
        if (off == 0.0 || off <= 1e-30 * all) break;
        for (int p = 0; p < n - 1; p++)
            for (int q = p + 1; q < n; q++)
                if (a[p * n + q] != 0.0) rotate(n, a, v, p, q);
    }
    if (sweep == MAX_SWEEPS) return -1;
    double d[4];
    int order[4];
    for (int i = 0; i < n; i++) d[i] = a[i * n + i];
    sort_desc(n, d, order);
    for (int k = 0; k < n; k++) {
        evals[k] = d[order[k]];
        for (int i = 0; i < n; i++) evecs[k * n + i] = v[i * n + order[k]];
    }
    return 0;
}
