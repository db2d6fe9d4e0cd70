/* vecmath.h: small dense linear algebra in double precision, shared by the measure module
 * and VMD's vector/matrix Tcl commands: 3-vectors, 4x4 transformation matrices in VMD's
 * row-major convention, rotations built as VMD builds them, and a Jacobi eigen-solver for
 * symmetric matrices up to 4x4. No Tcl, no molecules. */
#ifndef MS_VECMATH_H
#define MS_VECMATH_H

/* ---- 3-vectors */
static inline double ms_v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
void ms_v3_sub(const double a[3], const double b[3], double out[3]);   /* a - b */
void ms_v3_cross(const double a[3], const double b[3], double out[3]);
double ms_v3_length(const double a[3]);
/* Angle between two vectors in degrees, 0..180 (0 when either is zero). */
double ms_v3_angle(const double a[3], const double b[3]);
/* The dihedral angle a-b-c-d in degrees, -180..180, with the IUPAC sign convention. */
double ms_v3_dihedral(const double a[3], const double b[3], const double c[3], const double d[3]);

/* ---- 4x4 matrices: m[4 * row + col], acting on column vectors (x' = M x), which is how
 * VMD's Tcl matrices {{r0} {r1} {r2} {r3}} read. */
void ms_mat4d_identity(double m[16]);
/* out = a * b (out may be a or b). */
void ms_mat4d_mul(const double a[16], const double b[16], double out[16]);
void ms_mat4d_transpose(const double a[16], double out[16]);
/* General inverse by Gauss-Jordan elimination with partial pivoting; -1 when the matrix is
 * singular (or not finite), out untouched then. */
int ms_mat4d_inverse(const double a[16], double out[16]);
/* out = m * v for a 4-vector (in and out may alias). */
void ms_mat4d_apply(const double m[16], const double v[4], double out[4]);
/* Apply to a point (w = 1): rotation and translation. */
void ms_mat4d_apply_point(const double m[16], const double p[3], double out[3]);

void ms_mat4d_translation(double m[16], const double t[3]);
/* Right-handed rotation by `rad` radians about the x, y or z axis ('x', 'y', 'z'). */
void ms_mat4d_axis_rotation(double m[16], char axis, double rad);
/* Rotation by `rad` about a vector through the origin; a zero vector means the x axis, as
 * VMD's transabout does. */
void ms_mat4d_rotate_about(double m[16], const double axis[3], double rad);
/* VMD's transvec: the rotation taking the x axis onto the direction of v (about z, then y);
 * transvecinv is its inverse, taking v onto the x axis. Identity for a zero vector. */
void ms_mat4d_transvec(double m[16], const double v[3]);
void ms_mat4d_transvecinv(double m[16], const double v[3]);

/* ---- symmetric eigenproblem
 * Eigenvalues and eigenvectors of the symmetric n x n matrix a (row-major, n <= 4) by cyclic
 * Jacobi rotations. evals come out in decreasing order (ties keep their original order);
 * evecs holds the unit eigenvectors as rows, evecs[k * n + i] being component i of the k-th.
 * Returns 0, or -1 when the input is not finite or the iteration does not converge. */
int ms_eigen_sym(int n, const double *a, double *evals, double *evecs);

#endif
