/* vecmath.h: small dense linear algebra in double precision, shared by the measure module,
 * the tracers, QuickSurf and VMD's vector/matrix Tcl commands: 3-vectors, 4x4
 * transformation matrices in VMD's row-major convention (both from vec_tmpl.h, whose float
 * instance is vecf.h), rotations built as VMD builds them, 3x3 inverses and a Jacobi
 * eigen-solver for symmetric matrices up to 4x4. No Tcl, no molecules. */
#ifndef MS_VECMATH_H
#define MS_VECMATH_H

/* ---- 3-vectors (ms_v3_dot, _sub, _cross, _length, _normalize) and 4x4 matrices
 * (ms_mat4d_identity, _mul, _transpose, _translation, _scaling, _axis_rotation, _point,
 * _normal, _scale_factor): the double instance of vec_tmpl.h, where they are described.
 * vecf.h is the float one. */
#define MS_T double
#define MS_T_SQRT sqrt
#define MS_VEC(name) ms_v3_##name
#define MS_MAT(name) ms_mat4d_##name
#include "vecmath/vec_tmpl.h"

/* Angle between two vectors in degrees, 0..180 (0 when either is zero). */
double ms_v3_angle(const double a[3], const double b[3]);
/* The dihedral angle a-b-c-d in degrees, -180..180, with the IUPAC sign convention. */
double ms_v3_dihedral(const double a[3], const double b[3], const double c[3], const double d[3]);

/* General inverse by Gauss-Jordan elimination with partial pivoting; -1 when the matrix is
 * singular (or not finite), out untouched then. */
int ms_mat4d_inverse(const double a[16], double out[16]);
/* out = m * v for a 4-vector (in and out may alias). */
void ms_mat4d_apply(const double m[16], const double v[4], double out[4]);

/* Rotation by `rad` about a vector through the origin; a zero vector means the x axis, as
 * VMD's transabout does. */
void ms_mat4d_rotate_about(double m[16], const double axis[3], double rad);
/* VMD's transvec: the rotation taking the x axis onto the direction of v (about z, then y);
 * transvecinv is its inverse, taking v onto the x axis. Identity for a zero vector. */
void ms_mat4d_transvec(double m[16], const double v[3]);
void ms_mat4d_transvecinv(double m[16], const double v[3]);

/* ---- 3x3 matrices, a[row][col]
 * The inverse by cofactors over the determinant; -1 when the matrix is singular
 * (|det| <= 1e-30) or not finite, inv untouched then. */
int ms_m3d_inverse(const double a[3][3], double inv[3][3]);

/* ---- symmetric eigenproblem
 * Eigenvalues and eigenvectors of the symmetric n x n matrix a (row-major, n <= 4) by cyclic
 * Jacobi rotations. evals come out in decreasing order (ties keep their original order);
 * evecs holds the unit eigenvectors as rows, evecs[k * n + i] being component i of the k-th.
 * Returns 0, or -1 when the input is not finite or the iteration does not converge. */
int ms_eigen_sym(int n, const double *a, double *evals, double *evecs);

#endif
