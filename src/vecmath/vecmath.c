/* vecmath.c: the double-precision functions of vecmath.h that vec_tmpl.h does not give:
 * angles, the 4x4 inverse, VMD's rotations, the 3x3 inverse. */
#include "config.h"
#include "vecmath/vecmath.h"

#include <math.h>
#include <string.h>

#define RAD2DEG (180.0 / M_PI)

double ms_v3_angle(const double a[3], const double b[3])
{
    double la = ms_v3_length(a), lb = ms_v3_length(b);
    if (la == 0.0 || lb == 0.0) return 0.0;
    double c = ms_v3_dot(a, b) / (la * lb);
    if (c > 1.0) c = 1.0;
    if (c < -1.0) c = -1.0;
    return acos(c) * RAD2DEG;
}

double ms_v3_dihedral(const double a[3], const double b[3], const double c[3], const double d[3])
{
    double b1[3], b2[3], b3[3], n1[3], n2[3];
    ms_v3_sub(b, a, b1);
    ms_v3_sub(c, b, b2);
    ms_v3_sub(d, c, b3);
    ms_v3_cross(b1, b2, n1);
    ms_v3_cross(b2, b3, n2);
    /* atan2(|b2| b1.(b2 x b3), (b1 x b2).(b2 x b3)) */
    double y = ms_v3_dot(n1, b3) * ms_v3_length(b2);
    double x = ms_v3_dot(n1, n2);
    return atan2(y, x) * RAD2DEG;
}

/* ---------------------------------------------------------------- 4x4 matrices */

/* Swap rows r and s of both halves of the augmented system. */
static void swap_rows(double a[16], double b[16], int r, int s)
{
    for (int c = 0; c < 4; c++) {
        double t = a[4 * r + c];
        a[4 * r + c] = a[4 * s + c];
        a[4 * s + c] = t;
        t = b[4 * r + c];
        b[4 * r + c] = b[4 * s + c];
        b[4 * s + c] = t;
    }
}

int ms_mat4d_inverse(const double in[16], double out[16])
{
    double a[16], inv[16], scale = 0.0;
    memcpy(a, in, sizeof a);
    ms_mat4d_identity(inv);
    for (int k = 0; k < 16; k++) {
        if (!isfinite(a[k])) return -1;
        if (fabs(a[k]) > scale) scale = fabs(a[k]);
    }
    for (int col = 0; col < 4; col++) {
        int piv = col;
        for (int r = col + 1; r < 4; r++)
            if (fabs(a[4 * r + col]) > fabs(a[4 * piv + col])) piv = r;
        if (fabs(a[4 * piv + col]) <= 1e-12 * scale) return -1;
        if (piv != col) swap_rows(a, inv, piv, col);
        double d = 1.0 / a[4 * col + col];
        for (int c = 0; c < 4; c++) {
            a[4 * col + c] *= d;
            inv[4 * col + c] *= d;
        }
        for (int r = 0; r < 4; r++) {
            if (r == col || a[4 * r + col] == 0.0) continue;
            double f = a[4 * r + col];
            for (int c = 0; c < 4; c++) {
                a[4 * r + c] -= f * a[4 * col + c];
                inv[4 * r + c] -= f * inv[4 * col + c];
            }
        }
    }
    memcpy(out, inv, sizeof inv);
    return 0;
}

void ms_mat4d_apply(const double m[16], const double v[4], double out[4])
{
    double t[4];
    for (int r = 0; r < 4; r++)
        t[r] = m[4 * r] * v[0] + m[4 * r + 1] * v[1] + m[4 * r + 2] * v[2] + m[4 * r + 3] * v[3];
    memcpy(out, t, sizeof t);
}

/* Azimuth (about z) and elevation (towards z) of v. */
static void direction_angles(const double v[3], double *theta, double *phi)
{
    *theta = atan2(v[1], v[0]);
    *phi = atan2(v[2], sqrt(v[0] * v[0] + v[1] * v[1]));
}

void ms_mat4d_transvec(double m[16], const double v[3])
{
    double theta, phi, rz[16], ry[16];
    direction_angles(v, &theta, &phi);
    ms_mat4d_axis_rotation(rz, 'z', theta);
    ms_mat4d_axis_rotation(ry, 'y', -phi);
    ms_mat4d_mul(rz, ry, m);
}

void ms_mat4d_transvecinv(double m[16], const double v[3])
{
    double theta, phi, rz[16], ry[16];
    direction_angles(v, &theta, &phi);
    ms_mat4d_axis_rotation(ry, 'y', phi);
    ms_mat4d_axis_rotation(rz, 'z', -theta);
    ms_mat4d_mul(ry, rz, m);
}

void ms_mat4d_rotate_about(double m[16], const double axis[3], double rad)
{
    /* Rodrigues: R = cos I + sin [k]x + (1 - cos) k k^T for the unit axis k. This equals
     * VMD's transvec * Rx * transvecinv, which turns about x for a zero axis. */
    double len = ms_v3_length(axis), k[3] = {1.0, 0.0, 0.0};
    if (len > 0.0)
        for (int i = 0; i < 3; i++) k[i] = axis[i] / len;
    double c = cos(rad), s = sin(rad), t = 1.0 - c;
    double r[9] = {c + t * k[0] * k[0],        t * k[0] * k[1] - s * k[2], t * k[0] * k[2] + s * k[1],
                   t * k[0] * k[1] + s * k[2], c + t * k[1] * k[1],        t * k[1] * k[2] - s * k[0],
                   t * k[0] * k[2] - s * k[1], t * k[1] * k[2] + s * k[0], c + t * k[2] * k[2]};
    ms_mat4d_identity(m);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) m[4 * i + j] = r[3 * i + j];
}

/* ---------------------------------------------------------------- 3x3 matrices */

int ms_m3d_inverse(const double a[3][3], double inv[3][3])
{
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (!(fabs(det) > 1e-30) || !isfinite(det)) return -1;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            /* the cofactor of a[c][r] */
            int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            inv[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
        }
    return 0;
}
