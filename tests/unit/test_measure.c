/* test_measure.c: unit tests of src/vecmath and src/measure against values known
 * independently: analytic cases (a regular tetrahedron, a box of point masses, rotations
 * recovered by fitting, a mirror image, dihedrals of built geometry, the area of one sphere
 * and of two overlapping ones by the lens formula, g(r) of an ideal periodic gas), brute
 * force over all pairs, and numbers for the real structures in tests/data computed with
 * MDAnalysis, numpy and Biopython by tests/python/measure_refs.py (pasted below). */
#include "config.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "measure/measure.h"
#include "vecmath/vecmath.h"

#include <math.h>
#include <string.h>

#include "ms_testload.h"

static int near(double a, double b, double tol) { return fabs(a - b) <= tol; }
static int rel_near(double a, double b, double tol) { return fabs(a - b) <= tol * fabs(b); }

/* A deterministic pseudo-random number in [0, 1). */
static double rnd(void)
{
    static uint64_t s = 88172645463325252ull;
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return (double)(s >> 11) / 9007199254740992.0;
}

/* A molecule of n blank atoms (named "X", mass 1, radius 1) with one frame at xyz. */
static ms_molecule *make_mol(size_t n, const double *xyz)
{
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    ms_str blank = ms_strtab_intern_cstr(m->strings, "");
    ms_str x = ms_strtab_intern_cstr(m->strings, "X");
    for (size_t i = 0; i < n; i++) {
        ms_mol_add_blank_atom(m, &err);
        ms_atoms *a = &m->atoms;
        a->name[i] = a->type[i] = x;
        a->resname[i] = a->segname[i] = a->chain[i] = blank;
        a->mass[i] = a->radius[i] = 1.0f;
        a->residue[i] = (int32_t)i;
    }
    ms_frame *f = ms_mol_add_frame(m, 0, &err);
    for (size_t k = 0; k < 3 * n; k++) f->pos[k] = (float)xyz[k];
    m->frame = 0;
    return m;
}

/* Indices 0..n-1. */
static uint32_t *iota(size_t n)
{
    uint32_t *v = malloc((n ? n : 1) * sizeof *v);
    for (size_t i = 0; i < n; i++) v[i] = (uint32_t)i;
    return v;
}

/* Atoms of a chain (and name, when given), ascending; returns the count. */
static size_t pick(const ms_molecule *m, const char *chain, const char *name, uint32_t *out)
{
    size_t n = 0;
    for (size_t i = 0; i < m->atoms.n; i++)
        if (!strcmp(ms_mol_str(m, m->atoms.chain[i]), chain) &&
            (!name || !strcmp(ms_mol_str(m, m->atoms.name[i]), name)))
            out[n++] = (uint32_t)i;
    return n;
}

static double mat_diff(const double a[16], const double b[16])
{
    double d = 0;
    for (int k = 0; k < 16; k++) d = fmax(d, fabs(a[k] - b[k]));
    return d;
}

/* ---------------------------------------------------------------- vecmath */

static void test_matrices(void)
{
    t_suite = "vecmath";
    double a[16] = {2, 1, 0, 3, 0, 1, 4, -1, 1, 0, 1, 2, 0, 0, 0, 1}, inv[16], prod[16], id[16];
    ms_mat4d_identity(id);
    t_ok(ms_mat4d_inverse(a, inv) == 0, "inverse of an invertible matrix");
    ms_mat4d_mul(a, inv, prod);
    t_ok(mat_diff(prod, id) < 1e-12, "a * inverse(a) = identity (%g)", mat_diff(prod, id));
    double sing[16] = {1, 2, 3, 4, 2, 4, 6, 8, 0, 1, 0, 1, 0, 0, 0, 1};
    t_ok(ms_mat4d_inverse(sing, inv) == -1, "a singular matrix is refused");

    /* transabout = transvec * Rx * transvecinv, VMD's own construction, for any axis */
    double axis[3] = {0.3, -1.2, 2.0}, r[16], tv[16], rx[16], tvi[16], ref[16];
    ms_mat4d_rotate_about(r, axis, 0.7);
    ms_mat4d_transvec(tv, axis);
    ms_mat4d_axis_rotation(rx, 'x', 0.7);
    ms_mat4d_transvecinv(tvi, axis);
    ms_mat4d_mul(tv, rx, ref);
    ms_mat4d_mul(ref, tvi, ref);
    t_ok(mat_diff(r, ref) < 1e-12, "rotation about an axis matches transvec.Rx.transvecinv");
    double ex[3] = {1, 0, 0}, out[3], len = ms_v3_length(axis);
    ms_mat4d_point(tv, ex, out);
    t_ok(near(out[0], axis[0] / len, 1e-12) && near(out[1], axis[1] / len, 1e-12) &&
             near(out[2], axis[2] / len, 1e-12), "transvec takes x onto the vector's direction");
    double z[3] = {0, 0, 1}, q[3];
    ms_mat4d_axis_rotation(r, 'z', M_PI / 2);
    ms_mat4d_point(r, ex, q);
    t_ok(near(q[1], 1, 1e-12) && near(q[0], 0, 1e-12), "rotation about z turns x onto y");
    ms_mat4d_rotate_about(r, z, M_PI / 2);
    ms_mat4d_point(r, ex, q);
    t_ok(near(q[1], 1, 1e-12), "rotation about {0 0 1} turns x onto y");
}

static void test_eigen(void)
{
    int rc;
    t_suite = "vecmath";
    /* A = R diag(5, 2, -1) R^T for a known rotation R: eigenvalues 5 2 -1, vectors R's
     * columns. */
    double R[16], axis[3] = {1, 2, 2}, d[3] = {2, 5, -1}, A[9] = {0}, ev[3], vec[9];
    ms_mat4d_rotate_about(R, axis, 1.1);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) A[3 * i + j] += R[4 * i + k] * d[k] * R[4 * j + k];
    rc = ms_eigen_sym(3, A, ev, vec);
    t_ok(rc == 0, "3x3 eigen-solve converges");
    t_ok(near(ev[0], 5, 1e-12) && near(ev[1], 2, 1e-12) && near(ev[2], -1, 1e-12),
         "eigenvalues 5 2 -1 in decreasing order (%g %g %g)", ev[0], ev[1], ev[2]);
    double dot = fabs(vec[0] * R[1] + vec[1] * R[5] + vec[2] * R[9]);
    t_ok(near(dot, 1, 1e-12), "largest eigenvector is R's second column (|dot| %g)", dot);
    double nan[9] = {NAN, 0, 0, 0, 1, 0, 0, 0, 1};
    rc = ms_eigen_sym(3, nan, ev, vec);
    t_ok(rc == -1, "non-finite input is refused");
}

static void test_geometry(void)
{
    t_suite = "vecmath";
    /* a on +x, b at the origin, c on +z, d turned by phi about z: the dihedral is phi */
    double a[3] = {1, 0, 0}, b[3] = {0, 0, 0}, c[3] = {0, 0, 1};
    double phis[] = {60, -120, 180, 0, 15.5};
    for (size_t k = 0; k < MS_COUNTOF(phis); k++) {
        double p = phis[k] * M_PI / 180, d[3] = {cos(p), sin(p), 1};
        double got = ms_v3_dihedral(a, b, c, d);
        t_ok(near(fabs(got), fabs(phis[k]), 1e-9) && (phis[k] == 180 || near(got, phis[k], 1e-9)),
             "dihedral of built geometry %g (got %g)", phis[k], got);
    }
    double u[3] = {1, 0, 0}, v[3] = {1, 1, 0};
    t_ok(near(ms_v3_angle(u, v), 45, 1e-12), "angle between x and x+y is 45");
}

/* ---------------------------------------------------------------- one set */

static void test_tetrahedron(void)
{
    int rc;
    t_suite = "measure";
    double xyz[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    ms_molecule *m = make_mol(4, xyz);
    uint32_t *idx = iota(4);
    ms_atomset s = {m, 0, idx, 4};
    ms_error err = {{0}};
    double c[3], r, lo[3], hi[3], w[4] = {1, 0, 0, 0};
    rc = ms_measure_center(&s, NULL, c, &err);
    t_ok(rc == 0 && near(c[0], 0, 1e-12) && near(c[1], 0, 1e-12),
         "center of a regular tetrahedron is its middle");
    rc = ms_measure_center(&s, w, c, &err);
    t_ok(rc == 0 && near(c[0], 1, 1e-12) && near(c[2], 1, 1e-12), "weights pick one vertex");
    rc = ms_measure_rgyr(&s, NULL, &r, &err);
    t_ok(rc == 0 && near(r, sqrt(3.0), 1e-12), "rgyr of the tetrahedron is sqrt(3) (%g)", r);
    ms_inertia in;
    rc = ms_measure_inertia(&s, &in, &err);
    t_ok(rc == 0 && near(in.moments[0], 8, 1e-9) &&
             near(in.moments[2], 8, 1e-9), "inertia moments 8 8 8 (%g %g %g)", in.moments[0],
         in.moments[1], in.moments[2]);
    m->atoms.radius[1] = 2.5f;
    rc = ms_measure_minmax(&s, 1, lo, hi, &err);
    t_ok(rc == 0 && near(lo[0], -2, 1e-6) &&
             near(hi[0], 3.5, 1e-6) && near(lo[1], -3.5, 1e-6), "minmax with radii");
    rc = ms_measure_minmax(&s, 0, lo, hi, &err);
    t_ok(rc == 0 && near(lo[0], -1, 0) && near(hi[2], 1, 0), "minmax of centres");
    double zero[4] = {0, 0, 0, 0};
    rc = ms_measure_center(&s, zero, c, &err);
    t_ok(rc == -1 && strstr(err.msg, "sum to 0"), "zero weights are refused (%s)", err.msg);
    s.n = 0;
    rc = ms_measure_center(&s, NULL, c, &err);
    t_ok(rc == -1, "an empty set has no center");
    rc = ms_measure_minmax(&s, 0, lo, hi, &err);
    t_ok(rc == -1, "an empty set has no extent");
    s.frame = 3;
    t_ok(ms_atomset_check(&s, &err) == -1 && strstr(err.msg, "no frame 3"), "a missing frame");
    free(idx);
    ms_mol_free(m);
}

/* A box of 8 unit masses at (+-3, +-2, +-1): Ixx = 8 (4 + 1), Iyy = 8 (9 + 1), Izz = 8 (9 + 4);
 * turned by a rotation, the principal axes turn with it. */
static void test_inertia_box(void)
{
    int rc;
    t_suite = "measure";
    double xyz[24], R[16], axis[3] = {1, -1, 0.5};
    ms_mat4d_rotate_about(R, axis, 0.9);
    for (int k = 0; k < 8; k++) {
        double p[3] = {k & 1 ? 3 : -3, k & 2 ? 2 : -2, k & 4 ? 1 : -1};
        ms_mat4d_point(R, p, xyz + 3 * k);
        xyz[3 * k] += 10;   /* and moved off the origin */
    }
    ms_molecule *m = make_mol(8, xyz);
    uint32_t *idx = iota(8);
    ms_atomset s = {m, 0, idx, 8};
    ms_inertia in;
    ms_error err = {{0}};
    rc = ms_measure_inertia(&s, &in, &err);
    t_ok(rc == 0, "inertia of a box of masses");
    t_ok(near(in.moments[0], 104, 1e-4) && near(in.moments[1], 80, 1e-4) &&
             near(in.moments[2], 40, 1e-4), "moments 104 80 40 (%g %g %g)", in.moments[0],
         in.moments[1], in.moments[2]);
    t_ok(near(in.com[0], 10, 1e-5) && near(in.com[1], 0, 1e-5), "center of mass");
    /* the largest moment's axis is the rotated z axis, the smallest the rotated x */
    double dz = fabs(in.axes[0][0] * R[2] + in.axes[0][1] * R[6] + in.axes[0][2] * R[10]);
    double dx = fabs(in.axes[2][0] * R[0] + in.axes[2][1] * R[4] + in.axes[2][2] * R[8]);
    t_ok(near(dz, 1, 1e-6) && near(dx, 1, 1e-6), "principal axes follow the rotation");
    t_ok(near(in.tensor[0][1], in.tensor[1][0], 1e-9), "tensor is symmetric");
    free(idx);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- fitting */

static double fitted_rmsd(size_t n, const double *x, const double *y, const double m[16])
{
    double s = 0;
    for (size_t i = 0; i < n; i++) {
        double p[3], d[3];
        ms_mat4d_point(m, x + 3 * i, p);
        ms_v3_sub(p, y + 3 * i, d);
        s += ms_v3_dot(d, d);
    }
    return sqrt(s / (double)n);
}

static double det3(const double m[16])
{
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/* y = R x + t for a known R and t: the fit must give back exactly that motion. */
static void test_fit_rotation(void)
{
    int rc;
    t_suite = "measure";
    enum { N = 20 };
    double x[3 * N], y[3 * N], R[16], axis[3] = {1, 2, 3}, m[16], t[3] = {3, -2, 7};
    ms_error err = {{0}};
    ms_mat4d_rotate_about(R, axis, 37 * M_PI / 180);
    for (int k = 0; k < 3; k++) R[4 * k + 3] = t[k];
    for (int i = 0; i < 3 * N; i++) x[i] = 10 * rnd() - 5;
    for (int i = 0; i < N; i++) ms_mat4d_point(R, x + 3 * i, y + 3 * i);
    rc = ms_measure_fit_points(N, x, y, NULL, m, &err);
    t_ok(rc == 0, "fit of a rotated copy");
    t_ok(mat_diff(m, R) < 1e-10, "the rotation and translation come back (%g)", mat_diff(m, R));
    t_ok(fitted_rmsd(N, x, y, m) < 1e-10, "rmsd after applying it is 0");
    /* and the reverse direction is the inverse */
    double back[16], inv[16];
    ms_measure_fit_points(N, y, x, NULL, back, &err);
    ms_mat4d_inverse(R, inv);
    t_ok(mat_diff(back, inv) < 1e-10, "fitting y onto x gives the inverse motion");
    /* a zero weight on a displaced atom: the others still fit exactly */
    double w[N];
    for (int i = 0; i < N; i++) w[i] = 1 + i % 3;
    w[4] = 0;
    y[12] += 5;
    ms_measure_fit_points(N, x, y, w, m, &err);
    t_ok(mat_diff(m, R) < 1e-10, "an atom of weight 0 does not move the fit");
    for (int i = 0; i < N; i++) w[i] = 0;
    rc = ms_measure_fit_points(N, x, y, w, m, &err);
    t_ok(rc == -1, "all weights 0 is refused");
}

/* The fit must be a proper rotation even for a mirror image; for this chiral set the best
 * rotation leaves an RMSD of 0.925196195501 (numpy SVD Kabsch with the determinant
 * correction, measure_refs.py), and no random rotation does better. */
static void test_fit_mirror(void)
{
    int rc;
    t_suite = "measure";
    double x[15] = {0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3, 1, 1, 1}, y[15], m[16];
    ms_error err = {{0}};
    for (int i = 0; i < 15; i++) y[i] = i % 3 == 0 ? -x[i] : x[i];
    rc = ms_measure_fit_points(5, x, y, NULL, m, &err);
    t_ok(rc == 0, "fit of a mirror image");
    t_ok(near(det3(m), 1, 1e-12), "the fit is a rotation, not a reflection (det %g)", det3(m));
    double best = fitted_rmsd(5, x, y, m);
    t_ok(near(best, 0.925196195501, 1e-9), "best proper RMSD 0.925196195501 (%.12f)", best);
    int beaten = 0;
    for (int k = 0; k < 2000; k++) {
        double axis[3] = {rnd() - 0.5, rnd() - 0.5, rnd() - 0.5}, r[16], cx[3] = {0.4, 0.6, 0.8};
        double cy[3] = {-0.4, 0.6, 0.8}, rc[3];
        ms_mat4d_rotate_about(r, axis, 2 * M_PI * rnd());
        ms_mat4d_point(r, cx, rc);
        for (int j = 0; j < 3; j++) r[4 * j + 3] = cy[j] - rc[j];
        if (fitted_rmsd(5, x, y, r) < best - 1e-9) beaten++;
    }
    t_ok(beaten == 0, "no random rotation beats it (%d did)", beaten);
}

static void test_fit_degenerate(void)
{
    int rc;
    t_suite = "measure";
    double m[16];
    ms_error err = {{0}};
    double one_x[3] = {1, 2, 3}, one_y[3] = {-4, 0, 9};
    rc = ms_measure_fit_points(1, one_x, one_y, NULL, m, &err);
    t_ok(rc == 0 && near(m[0], 1, 1e-12) &&
             near(m[5], 1, 1e-12) && near(m[3], -5, 1e-12) && near(m[11], 6, 1e-12),
         "one atom: a pure translation");
    double two_x[6] = {0, 0, 0, 2, 0, 0}, two_y[6] = {5, 5, 5, 5, 7, 5};
    rc = ms_measure_fit_points(2, two_x, two_y, NULL, m, &err);
    t_ok(rc == 0 &&
             fitted_rmsd(2, two_x, two_y, m) < 1e-12 && near(det3(m), 1, 1e-12),
         "two atoms are laid on their targets");
    double line_x[9] = {0, 0, 0, 1, 1, 1, 3, 3, 3};
    double line_y[9] = {1, 0, 0, 1, 0, sqrt(3.0), 1, 0, 3 * sqrt(3.0)};
    rc = ms_measure_fit_points(3, line_x, line_y, NULL, m, &err);
    t_ok(rc == 0 && fitted_rmsd(3, line_x, line_y, m) < 1e-12, "collinear atoms fit exactly");
    rc = ms_measure_fit_points(0, line_x, line_y, NULL, m, &err);
    t_ok(rc == -1, "no atoms: refused");
}

/* Atom sets of a two-frame molecule: frame 1 = frame 0 moved by a known motion, stored as
 * float; fit, rmsd, order and the error paths through ms_atomset. */
static void test_fit_sets(void)
{
    int rc;
    t_suite = "measure";
    enum { N = 30 };
    double x[3 * N], R[16], axis[3] = {-1, 0.2, 0.4}, m[16], r;
    ms_error err = {{0}};
    for (int i = 0; i < 3 * N; i++) x[i] = 20 * rnd() - 10;
    ms_molecule *mol = make_mol(N, x);
    ms_frame *f = ms_mol_add_frame(mol, 0, &err);
    ms_mat4d_rotate_about(R, axis, 2.0);
    R[3] = 1, R[7] = 2, R[11] = -3;
    for (int i = 0; i < N; i++) {
        double p[3];
        ms_mat4d_point(R, x + 3 * i, p);
        for (int k = 0; k < 3; k++) f->pos[3 * i + k] = (float)p[k];
    }
    uint32_t *idx = iota(N), order[N];
    ms_atomset a = {mol, 0, idx, N}, b = {mol, 1, idx, N};
    rc = ms_measure_fit(&a, &b, NULL, NULL, m, &err);
    t_ok(rc == 0 && mat_diff(m, R) < 1e-5,
         "fit between frames recovers the motion (%g)", mat_diff(m, R));
    /* a second molecule holding the moved atoms in reverse order: order pairs them up */
    double xr[3 * N];
    for (int i = 0; i < N; i++)
        for (int k = 0; k < 3; k++) xr[3 * i + k] = f->pos[3 * (N - 1 - i) + k];
    ms_molecule *mol2 = make_mol(N, xr);
    ms_atomset b2 = {mol2, 0, idx, N};
    double m2[16];
    for (int i = 0; i < N; i++) order[i] = (uint32_t)(N - 1 - i);
    rc = ms_measure_fit(&a, &b2, NULL, order, m2, &err);
    t_ok(rc == 0 && mat_diff(m2, R) < 1e-5,
         "order pairs atom i with atom order[i] of the second set");
    rc = ms_measure_fit(&a, &b2, NULL, NULL, m2, &err);
    t_ok(rc == 0 && mat_diff(m2, R) > 0.1, "without the order the fit is different");
    ms_mol_free(mol2);
    for (int i = 0; i < N; i++) order[i] = (uint32_t)i;
    rc = ms_measure_fit(&a, &b, NULL, order, m2, &err);
    t_ok(rc == 0 && mat_diff(m2, m) < 1e-12, "the identity order changes nothing");
    order[0] = N;
    rc = ms_measure_fit(&a, &b, NULL, order, m2, &err);
    t_ok(rc == -1, "an order index out of range");
    /* rmsd: frame 0 against itself moved by (1 2 2): exactly 3 */
    for (int i = 0; i < 3 * N; i++) f->pos[i] = (float)(x[i] + (i % 3 == 0 ? 1 : 2));
    rc = ms_measure_rmsd(&a, &b, NULL, &r, &err);
    t_ok(rc == 0 && near(r, 3, 1e-5), "rmsd of a shift by " "(1 2 2) is 3 (%g)", r);
    ms_atomset shorter = {mol, 1, idx, N - 1};
    rc = ms_measure_rmsd(&a, &shorter, NULL, &r, &err);
    t_ok(rc == -1 && strstr(err.msg, "same number"), "different atom counts are refused");
    rc = ms_measure_fit(&a, &shorter, NULL, NULL, m, &err);
    t_ok(rc == -1, "fit refuses them too");
    free(idx);
    ms_mol_free(mol);
}

/* ---------------------------------------------------------------- frames */

/* Atom i moves by k d_i in frame k = 0..K-1: the average is x + d (K - 1) / 2 and the RMS
 * fluctuation |d| sqrt((K^2 - 1) / 12). */
static void test_trajectory(void)
{
    int rc;
    t_suite = "measure";
    enum { N = 5, K = 7 };
    double x[3 * N], d[3 * N];
    ms_error err = {{0}};
    for (int i = 0; i < 3 * N; i++) x[i] = 10 * rnd(), d[i] = rnd() - 0.5;
    ms_molecule *m = make_mol(N, x);
    for (int k = 1; k < K; k++) {
        ms_frame *f = ms_mol_add_frame(m, 0, &err);
        for (int i = 0; i < 3 * N; i++) f->pos[i] = (float)(x[i] + k * d[i]);
    }
    for (int i = 0; i < 3 * N; i++) x[i] = m->frames[0].pos[i];
    uint32_t atoms[2] = {1, 3};
    double av[6], rf[2];
    ms_frame_range r;
    rc = ms_frame_range_make(m, 0, -1, 1, &r, &err);
    t_ok(rc == 0 && r.last == K - 1, "all frames");
    rc = ms_measure_avpos(m, atoms, 2, &r, av, &err);
    t_ok(rc == 0 &&
             near(av[0], x[3] + d[3] * (K - 1) / 2.0, 1e-5) &&
             near(av[5], x[11] + d[11] * (K - 1) / 2.0, 1e-5), "average positions");
    double want = ms_v3_length(d + 9) * sqrt((K * K - 1) / 12.0);
    rc = ms_measure_rmsf(m, atoms, 2, &r, rf, &err);
    t_ok(rc == 0 && near(rf[1], want, 1e-5), "RMS fluctuation (%g, expected %g)", rf[1], want);
    ms_frame_range_make(m, 2, 2, 1, &r, &err);
    rc = ms_measure_rmsf(m, atoms, 2, &r, rf, &err);
    t_ok(rc == 0 && rf[0] == 0, "one frame: no fluctuation");
    ms_frame_range_make(m, 0, 6, 3, &r, &err);   /* frames 0 3 6: average = frame 3 */
    rc = ms_measure_avpos(m, atoms, 2, &r, av, &err);
    t_ok(rc == 0 && near(av[0], x[3] + 3 * d[3], 1e-5), "first/last/step");
    rc = ms_frame_range_make(m, 3, 2, 1, &r, &err);
    t_ok(rc == -1, "last before first is refused");
    rc = ms_frame_range_make(m, 0, 7, 1, &r, &err);
    t_ok(rc == -1, "a frame past the end is refused");
    rc = ms_frame_range_make(m, 0, -1, 0, &r, &err);
    t_ok(rc == -1, "step 0 is refused");
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- pairs */

static int has_pair(const ms_pairs *p, uint32_t a, uint32_t b)
{
    for (size_t k = 0; k < p->n; k++)
        if (p->a[k] == a && p->b[k] == b) return 1;
    return 0;
}

static void bond(ms_molecule *m, uint32_t i, uint32_t j)
{
    ms_error err = {{0}};
    uint32_t pair[2] = {i, j};
    ms_mol_set_bonds(m, 1, pair, NULL, &err);
}

/* Five atoms: 0 1 2 3 on x at 0 1 2 4, atom 4 a hair above atom 0. */
static void test_contacts(void)
{
    int rc;
    t_suite = "measure";
    double xyz[15] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 4, 0, 0, 0, 0, 0.01};
    ms_molecule *m = make_mol(5, xyz);
    ms_error err = {{0}};
    uint32_t *all = iota(5), a_idx[2] = {0, 1}, b_idx[4] = {1, 2, 3, 4};
    ms_atomset s = {m, 0, all, 5}, a = {m, 0, a_idx, 2}, b = {m, 0, b_idx, 4};
    ms_pairs p;
    rc = ms_measure_contacts(&s, NULL, 1.5, &p, &err);
    t_ok(rc == 0 && p.n == 3 && has_pair(&p, 0, 1) &&
             has_pair(&p, 1, 2) && has_pair(&p, 1, 4), "one set: each pair once, not the "
         "coincident atoms (%zu pairs)", p.n);
    t_ok(p.n == 3 && p.a[0] == 0 && p.a[1] == 1 && p.b[1] == 2, "pairs sorted");
    ms_pairs_free(&p);
    rc = ms_measure_contacts(&s, NULL, 1.0, &p, &err);
    t_ok(rc == 0 && p.n == 2, "cutoff is inclusive " "(%zu)", p.n);
    ms_pairs_free(&p);
    rc = ms_measure_contacts(&a, &b, 1.5, &p, &err);
    t_ok(rc == 0 && p.n == 4 && has_pair(&p, 0, 4) &&
             has_pair(&p, 0, 1) && has_pair(&p, 1, 2) && has_pair(&p, 1, 4),
         "two sets of one frame: shared atom 1 not paired with itself (%zu pairs)", p.n);
    ms_pairs_free(&p);
    bond(m, 0, 1);
    rc = ms_measure_contacts(&s, NULL, 1.5, &p, &err);
    t_ok(rc == 0 && p.n == 2 && !has_pair(&p, 0, 1), "bonded atoms are not contacts");
    ms_pairs_free(&p);
    ms_frame *f = ms_mol_add_frame(m, 0, &err);
    memcpy(f->pos, m->frames[0].pos, 15 * sizeof(float));
    ms_atomset a1 = {m, 1, a_idx, 2};
    rc = ms_measure_contacts(&a, &a1, 1.5, &p, &err);
    t_ok(rc == 0 && p.n == 2 && has_pair(&p, 0, 0) &&
             has_pair(&p, 1, 1), "two frames: every pair, an atom with itself too, minus bonds");
    ms_pairs_free(&p);
    rc = ms_measure_contacts(&s, NULL, -1, &p, &err);
    t_ok(rc == 0 && p.n == 0, "negative cutoff");
    ms_pairs_free(&p);
    free(all);
    ms_mol_free(m);
}

/* O1-H1 ... O2 in a straight line, and O2-H2 pointing away. */
static ms_molecule *water_pair(double bend_deg)
{
    double b = bend_deg * M_PI / 180;
    double xyz[12] = {0, 0, 0, 0.96, 0, 0, 0.96 + 1.94 * cos(b), 1.94 * sin(b), 0, 0, 0, 0};
    xyz[9] = xyz[6] + 0.6, xyz[10] = xyz[7] + 0.77;
    ms_molecule *m = make_mol(4, xyz);
    ms_error err = {{0}};
    uint32_t pairs[4] = {0, 1, 2, 3};
    ms_mol_set_bonds(m, 2, pairs, NULL, &err);
    m->atoms.flags[1] |= MS_AF_HYDROGEN;
    m->atoms.flags[3] |= MS_AF_HYDROGEN;
    return m;
}

static void test_hbonds(void)
{
    int rc;
    t_suite = "measure";
    ms_molecule *m = water_pair(0);
    ms_error err = {{0}};
    uint32_t *all = iota(4), don[1] = {0}, acc[1] = {2}, rd[2] = {2, 3}, ra[2] = {0, 1};
    ms_atomset s = {m, 0, all, 4};
    ms_hbonds h;
    rc = ms_measure_hbonds(&s, NULL, 3.0, 20, &h, &err);
    t_ok(rc == 0 && h.n == 1 && h.donor[0] == 0 &&
             h.acceptor[0] == 2 && h.hydrogen[0] == 1, "a straight O-H...O bond (%zu)", h.n);
    ms_hbonds_free(&h);
    rc = ms_measure_hbonds(&s, NULL, 2.8, 20, &h, &err);
    t_ok(rc == 0 && h.n == 0, "too far at 2.8");
    ms_hbonds_free(&h);
    ms_atomset d = {m, 0, don, 1}, a = {m, 0, acc, 1}, d2 = {m, 0, rd, 2}, a2 = {m, 0, ra, 2};
    rc = ms_measure_hbonds(&d, &a, 3.0, 20, &h, &err);
    t_ok(rc == 0 && h.n == 1, "donor and acceptor sets");
    ms_hbonds_free(&h);
    rc = ms_measure_hbonds(&d2, &a2, 3.0, 20, &h, &err);
    t_ok(rc == 0 && h.n == 0, "the roles are not swapped with two sets");
    ms_hbonds_free(&h);
    ms_mol_free(m);
    m = water_pair(25);
    s.mol = m;
    rc = ms_measure_hbonds(&s, NULL, 3.0, 20, &h, &err);
    t_ok(rc == 0 && h.n == 0, "bent by 25: not " "within 20 degrees");
    ms_hbonds_free(&h);
    rc = ms_measure_hbonds(&s, NULL, 3.0, 30, &h, &err);
    t_ok(rc == 0 && h.n == 1, "but within 30");
    ms_hbonds_free(&h);
    uint32_t pairs[6] = {0, 1, 2, 3, 0, 2};
    ms_mol_set_bonds(m, 3, pairs, NULL, &err);
    rc = ms_measure_hbonds(&s, NULL, 3.0, 30, &h, &err);
    t_ok(rc == 0 && h.n == 0, "bonded D-A excluded");
    ms_hbonds_free(&h);
    free(all);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- surface area */

/* The area of sphere 1 (radius r1) outside sphere 2 (r2) at distance d: 4 pi r1^2 minus the
 * cap 2 pi r1 h1, h1 = r1 - (d^2 + r1^2 - r2^2) / (2 d). */
static double lens_outside(double r1, double r2, double d)
{
    double h = r1 - (d * d + r1 * r1 - r2 * r2) / (2 * d);
    return 4 * M_PI * r1 * r1 - 2 * M_PI * r1 * h;
}

static void test_sasa_spheres(void)
{
    int rc;
    t_suite = "measure";
    double xyz[6] = {0, 0, 0, 2.5, 0, 0}, area;
    ms_molecule *m = make_mol(2, xyz);
    m->atoms.radius[0] = 1.0f, m->atoms.radius[1] = 2.0f;
    uint32_t *idx = iota(2), first[1] = {0};
    ms_atomset one = {m, 0, idx, 1}, two = {m, 0, idx, 2};
    ms_sasa_opts o = {1.4, 500, NULL, 0, 0};
    ms_error err = {{0}};
    rc = ms_measure_sasa(&one, &o, &area, NULL, NULL, &err);
    t_ok(rc == 0 &&
             near(area, 4 * M_PI * 2.4 * 2.4, 1e-9), "one sphere: 4 pi (r + probe)^2 (%g)", area);
    o.srad = 0, o.samples = 4000;
    double want = lens_outside(1, 2, 2.5) + lens_outside(2, 1, 2.5);
    rc = ms_measure_sasa(&two, &o, &area, NULL, NULL, &err);
    t_ok(rc == 0 && rel_near(area, want, 2e-3),
         "two overlapping spheres: the lens formula (%g, expected %g)", area, want);
    o.srad = 0.5;
    want = lens_outside(1.5, 2.5, 2.5) + lens_outside(2.5, 1.5, 2.5);
    rc = ms_measure_sasa(&two, &o, &area, NULL, NULL, &err);
    t_ok(rc == 0 && rel_near(area, want, 2e-3),
         "with a probe radius (%g, expected %g)", area, want);
    o.restrict_to = first, o.nrestrict = 1, o.want_points = 1;
    float *pts;
    size_t np;
    want = lens_outside(1.5, 2.5, 2.5);
    rc = ms_measure_sasa(&two, &o, &area, &pts, &np, &err);
    t_ok(rc == 0 && rel_near(area, want, 3e-3),
         "-restrict counts only atom 0 (%g, expected %g)", area, want);
    int on_sphere = 1;
    for (size_t k = 0; k < np; k++) {
        float *p = pts + 3 * k;
        double d0 = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        double d1 = sqrt((p[0] - 2.5) * (p[0] - 2.5) + p[1] * p[1] + p[2] * p[2]);
        if (!near(d0, 1.5, 1e-5) || d1 < 2.5) on_sphere = 0;
    }
    t_ok(np > 0 && on_sphere && near(area, 4 * M_PI * 1.5 * 1.5 * (double)np / 4000, 1e-9),
         "the %zu points lie on atom 0's sphere outside atom 1's and match the area", np);
    free(pts);
    o.samples = 0;
    rc = ms_measure_sasa(&two, &o, &area, NULL, NULL, &err);
    t_ok(rc == -1, "0 samples is refused");
    free(idx);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- g(r) */

static void set_cell(ms_molecule *m, double a, double b, double c, double al, double be, double ga)
{
    float cell[6] = {(float)a, (float)b, (float)c, (float)al, (float)be, (float)ga};
    for (size_t f = 0; f < m->nframes; f++) memcpy(m->frames[f].cell, cell, sizeof cell);
}

/* n points uniform in the cell spanned by the columns of H. */
static ms_molecule *gas(size_t n, const double H[9])
{
    double *xyz = malloc(3 * n * sizeof *xyz);
    for (size_t i = 0; i < n; i++) {
        double s[3] = {rnd(), rnd(), rnd()};
        for (int k = 0; k < 3; k++)
            xyz[3 * i + k] = H[3 * k] * s[0] + H[3 * k + 1] * s[1] + H[3 * k + 2] * s[2];
    }
    ms_molecule *m = make_mol(n, xyz);
    free(xyz);
    return m;
}

/* An ideal gas: g(r) = 1 and the running integral rho 4/3 pi r^3, orthorhombic and
 * triclinic. */
static void test_gofr_gas(void)
{
    int rc;
    t_suite = "measure";
    enum { N = 3000 };
    ms_error err = {{0}};
    ms_gofr_result r;
    double ortho[9] = {30, 0, 0, 0, 30, 0, 0, 0, 30};
    double g60 = M_PI / 3, tric[9] = {30, 30 * cos(g60), 0, 0, 30 * sin(g60), 0, 0, 0, 30};
    const double *cells[2] = {ortho, tric};
    for (int c = 0; c < 2; c++) {
        ms_molecule *m = gas(N, cells[c]);
        set_cell(m, 30, 30, 30, 90, 90, c ? 60 : 90);
        uint32_t *idx = iota(N);
        ms_gofr *g = ms_gofr_new(0.1, 12.9, 1, &err);
        rc = g ? ms_gofr_add_frame(g, m, 0, idx, N, idx, N, &err) : -1;
        t_ok(rc == 0, "g(r) of a gas (%s)", err.msg);
        ms_gofr_get(g, &r);
        double mean = 0, worst = 0, volume = c ? 30 * 30 * 30 * sin(g60) : 27000;
        size_t used = 0;
        for (size_t i = 20; i < r.nbins; i++)
            if (r.gofr[i] > 0) mean += r.gofr[i], used++, worst = fmax(worst, fabs(r.gofr[i] - 1));
        mean /= (double)used;
        /* 130 bins; the triclinic cell's shortest width is 30 sin 60 = 25.98, so its g(r)
         * stops at 12.99: 129 bins */
        size_t last = c ? 128 : 129;
        double rr = 0.1 * (double)(last + 1);
        double ideal = (N - 1) / volume * 4.0 / 3.0 * M_PI * rr * rr * rr;
        t_ok(near(mean, 1, 0.01) && worst < 0.12 && used == last - 19, "%s gas: g(r) = 1 (mean %g, "
             "worst %g, %zu bins)", c ? "triclinic" : "orthorhombic", mean, worst, used);
        t_ok(rel_near(r.numint[last], ideal, 0.01), "running integral rho 4/3 pi r^3 (%g, %g)",
             r.numint[last], ideal);
        t_ok(r.frames_total == 1 && r.frames_done == 1 && rel_near(r.r[5], 0.55, 1e-12),
             "frame counts and bin centres");
        ms_gofr_free(g);
        free(idx);
        ms_mol_free(m);
    }
}

static void mat3_apply(const double M[9], const double v[3], double out[3])
{
    for (int k = 0; k < 3; k++) out[k] = M[3 * k] * v[0] + M[3 * k + 1] * v[1] + M[3 * k + 2] * v[2];
}

/* Brute force over all pairs and the 27 images around the nearest one in a skewed cell,
 * against the grid's histogram: up to half the shortest cell width, where a pair has at most
 * one image in reach. Some atoms lie outside the cell. */
static void test_gofr_triclinic_brute(void)
{
    t_suite = "measure";
    enum { N = 300 };
    double a = 14, b = 16, c = 15, al = 70, be = 80, ga = 65, d2r = M_PI / 180, delta = 0.25;
    double cy = (cos(al * d2r) - cos(be * d2r) * cos(ga * d2r)) / sin(ga * d2r);
    double H[9] = {a, b * cos(ga * d2r), c * cos(be * d2r), 0, b * sin(ga * d2r), c * cy, 0, 0,
                   c * sqrt(1 - cos(be * d2r) * cos(be * d2r) - cy * cy)};
    double vol = H[0] * H[4] * H[8], wmin = INFINITY;
    double Hi[9] = {1 / H[0], -H[1] / (H[0] * H[4]), (H[1] * H[5] - H[2] * H[4]) / vol,
                    0,        1 / H[4],              -H[5] / (H[4] * H[8]),
                    0,        0,                     1 / H[8]};
    for (int k = 0; k < 3; k++) wmin = fmin(wmin, 1 / ms_v3_length(Hi + 3 * k));
    size_t hmax = (size_t)(wmin / 2 / delta);
    ms_molecule *m = gas(N, H);
    set_cell(m, a, b, c, al, be, ga);
    for (int i = 0; i < 3 * 20; i++) m->frames[0].pos[i] += 40.0f;
    const float *p = m->frames[0].pos;
    double brute[100] = {0};
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double d[3], f[3];
            for (int k = 0; k < 3; k++) d[k] = (double)p[3 * j + k] - p[3 * i + k];
            mat3_apply(Hi, d, f);
            for (int k = 0; k < 3; k++) f[k] -= floor(f[k] + 0.5);
            for (int t = 0; t < 27; t++) {
                double e[3], q[3] = {f[0] + t % 3 - 1, f[1] + t / 3 % 3 - 1, f[2] + t / 9 - 1};
                mat3_apply(H, q, e);
                double dist = ms_v3_length(e);
                if (i == j && dist < 1e-6) continue;
                if (dist < delta * (double)hmax) brute[(size_t)(dist / delta)]++;
            }
        }
    ms_error err = {{0}};
    uint32_t *idx = iota(N);
    ms_gofr *g = ms_gofr_new(delta, 20, 1, &err);
    ms_gofr_add_frame(g, m, 0, idx, N, idx, N, &err);
    ms_gofr_result r;
    ms_gofr_get(g, &r);
    int same = hmax > 10 && hmax < 100;
    for (size_t i = 0; i < r.nbins; i++) same &= near(r.hist[i], i < hmax ? brute[i] : 0, 0);
    t_ok(same, "triclinic histogram up to %g equals the brute force over images", delta * hmax);
    ms_gofr_free(g);
    free(idx);
    ms_mol_free(m);
}

/* VMD's normalisation without periodic boundaries: 30 A^3 per atom of the first set. */
static void test_gofr_plain(void)
{
    int rc;
    t_suite = "measure";
    double xyz[6] = {0, 0, 0, 1.05, 0, 0};
    ms_molecule *m = make_mol(2, xyz);
    uint32_t *idx = iota(2);
    ms_error err = {{0}};
    ms_gofr_result r;
    double shell = 4.0 / 3.0 * M_PI * (1.1 * 1.1 * 1.1 - 1.0);
    ms_gofr *g = ms_gofr_new(0.1, 2, 0, &err);
    ms_gofr_add_frame(g, m, 0, idx, 1, idx + 1, 1, &err);
    ms_gofr_get(g, &r);
    t_ok(r.nbins == 21 && r.hist[10] == 1 && near(r.gofr[10], 30 / shell, 1e-9) &&
             r.numint[10] == 1 && r.numint[20] == 1 && r.numint[9] == 0,
         "one pair at 1.05: bin 10, g = 30 / shell volume (%g)", r.gofr[10]);
    ms_gofr_free(g);
    g = ms_gofr_new(0.1, 2, 0, &err);
    ms_gofr_add_frame(g, m, 0, idx, 2, idx, 2, &err);
    ms_gofr_add_frame(g, m, 0, idx, 2, idx, 0, &err);
    ms_gofr_get(g, &r);
    t_ok(r.hist[0] == 0 && near(r.hist[10], 1, 0) && near(r.gofr[10], 30 / shell, 1e-9),
         "an atom is not paired with itself; two frames average (%g)", r.hist[10]);
    t_ok(r.frames_total == 2 && r.frames_skipped == 1 && r.frames_done == 1,
         "an empty selection skips the frame");
    ms_gofr_free(g);
    g = ms_gofr_new(0.1, 2, 1, &err);
    rc = ms_gofr_add_frame(g, m, 0, idx, 2, idx, 2, &err);
    t_ok(rc == -1 && strstr(err.msg, "no volume"),
         "periodic without a cell is refused (%s)", err.msg);
    ms_gofr_free(g);
    t_ok(!ms_gofr_new(0, 2, 0, &err) && !ms_gofr_new(0.1, -1, 0, &err), "bad delta or rmax");
    free(idx);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- real structures */

/* 1tii, all atoms; numbers from measure_refs.py (MDAnalysis + numpy). */
static void test_1tii(void)
{
    int rc;
    t_suite = "measure/1tii";
    ms_molecule *m = load("1tii.pdb");
    if (!m) return;
    ms_error err = {{0}};
    uint32_t *all = iota(m->atoms.n);
    ms_atomset s = {m, 0, all, m->atoms.n};
    double c[3], r, lo[3], hi[3], *mass = malloc(m->atoms.n * sizeof *mass);
    ms_measure_atom_values(&s, "mass", mass, &err);
    rc = ms_measure_center(&s, NULL, c, &err);
    t_ok(rc == 0 && near(c[0], 51.66529047, 1e-5) &&
             near(c[1], 11.51879381, 1e-5) && near(c[2], 10.19571041, 1e-5), "center");
    rc = ms_measure_center(&s, mass, c, &err);
    t_ok(rc == 0 && near(c[0], 51.71857353, 1e-5) &&
             near(c[1], 11.49373134, 1e-5) && near(c[2], 10.24608503, 1e-5), "mass center");
    rc = ms_measure_rgyr(&s, NULL, &r, &err);
    t_ok(rc == 0 && near(r, 26.580491754382944, 1e-5), "rgyr");
    rc = ms_measure_rgyr(&s, mass, &r, &err);
    t_ok(rc == 0 && near(r, 26.596706071366892, 1e-5), "mass-weighted rgyr");
    rc = ms_measure_minmax(&s, 0, lo, hi, &err);
    t_ok(rc == 0 && near(lo[0], 11.59, 1e-4) &&
             near(lo[1], -22.877, 1e-4) && near(lo[2], -28.27, 1e-4) && near(hi[0], 84.681, 1e-4) &&
             near(hi[1], 40.101, 1e-4) && near(hi[2], 47.233, 1e-4), "minmax");
    rc = ms_measure_minmax(&s, 1, lo, hi, &err);
    t_ok(rc == 0 && near(lo[0], 10.07, 1e-4) &&
             near(lo[2], -29.79, 1e-4) && near(hi[0], 86.231, 1e-4) && near(hi[2], 48.783, 1e-4),
         "minmax -withradii (Bondi radii)");
    ms_inertia in;
    rc = ms_measure_inertia(&s, &in, &err);
    t_ok(rc == 0 && rel_near(in.moments[0], 40869964.5308567, 1e-6) &&
             rel_near(in.moments[1], 38269014.3752256, 1e-6) &&
             rel_near(in.moments[2], 28634725.932428055, 1e-6), "inertia moments");
    free(mass);
    free(all);
    ms_mol_free(m);
}

static void test_1tii_pairs(void)
{
    t_suite = "measure/1tii";
    ms_molecule *m = load("1tii.pdb");
    if (!m) return;
    ms_error err = {{0}};
    uint32_t *d = malloc(m->atoms.n * 4), *e = malloc(m->atoms.n * 4);
    size_t nd = pick(m, "D", "CA", d), ne = pick(m, "E", "CA", e);
    ms_atomset a = {m, 0, d, nd}, b = {m, 0, e, ne};
    double r, mat[16];
    int rc = ms_measure_rmsd(&a, &b, NULL, &r, &err);
    t_ok(nd == 98 && ne == 98 && rc == 0 &&
             near(r, 25.29549611260718, 1e-5), "CA rmsd of chains D and E (%g)", r);
    rc = ms_measure_fit(&a, &b, NULL, NULL, mat, &err);
    t_ok(rc == 0, "fit chain D onto chain E");
    double *x = malloc(nd * 3 * sizeof *x), *y = malloc(nd * 3 * sizeof *y);
    for (size_t i = 0; i < nd; i++)
        for (int k = 0; k < 3; k++)
            x[3 * i + k] = m->frames[0].pos[3 * d[i] + k],
            y[3 * i + k] = m->frames[0].pos[3 * e[i] + k];
    r = fitted_rmsd(nd, x, y, mat);
    t_ok(near(r, 0.2630933404232833, 1e-5), "RMSD after the fit equals the SVD optimum (%g)", r);
    nd = pick(m, "D", NULL, d), ne = pick(m, "E", NULL, e);
    a.n = nd, b.n = ne;
    ms_pairs p;
    rc = ms_measure_contacts(&a, &b, 3.5, &p, &err);
    t_ok(rc == 0 && p.n == 36 && p.a[0] == 3 &&
             p.b[0] == 927, "36 contacts within 3.5 between chains D and E (%zu)", p.n);
    ms_pairs_free(&p);
    /* chain D alone: 1432 unbonded pairs within 3.0 (numpy with VMD's bond rule), and every
     * pair within 1.7 is bonded */
    rc = ms_measure_contacts(&a, NULL, 3.0, &p, &err);
    t_ok(rc == 0 && p.n == 1432, "1432 contacts within chain D at 3.0 (%zu)", p.n);
    ms_pairs_free(&p);
    rc = ms_measure_contacts(&a, NULL, 1.7, &p, &err);
    t_ok(rc == 0 && p.n == 0, "bonded pairs are no contacts (%zu)", p.n);
    ms_pairs_free(&p);
    rc = ms_measure_contacts(&a, &b, 4.0, &p, &err);
    t_ok(rc == 0 && p.n == 174, "174 within 4.0 (%zu)", p.n);
    ms_pairs_free(&p);
    /* surface of chain D alone: Biopython's Shrake-Rupley with 5000 points gives 6099.4658 */
    double area;
    ms_sasa_opts o = {1.4, 500, NULL, 0, 0};
    rc = ms_measure_sasa(&a, &o, &area, NULL, NULL, &err);
    t_ok(rc == 0 && rel_near(area, 6099.4658, 0.01),
         "SASA of chain D, 500 points (%g, Biopython 6099.47)", area);
    o.samples = 5000;
    rc = ms_measure_sasa(&a, &o, &area, NULL, NULL, &err);
    t_ok(rc == 0 && rel_near(area, 6099.4658, 0.003), "SASA of chain D, 5000 points (%g)", area);
    free(x), free(y), free(d), free(e);
    ms_mol_free(m);
}

/* O-O g(r) of 216 waters in their 18.774349 A box; brute force with VMD's normalisation in
 * measure_refs.py. Up to 9 A every pair has one image in reach; up to 15 A (133 bins are
 * normalised, sqrt(1/2) of the side) only the minimum image counts and the shells lose the
 * caps beyond the faces. */
typedef struct gofr_ref {
    int bin;
    double hist, g, numint;
} gofr_ref;

static void check_water(ms_molecule *m, const uint32_t *o, size_t n, double rmax, size_t nbins,
                        size_t hmax, const gofr_ref *ref, size_t nref)
{
    ms_error err = {{0}};
    ms_gofr *g = ms_gofr_new(0.1, rmax, 1, &err);
    ms_gofr_result r;
    int rc = ms_gofr_add_frame(g, m, 0, o, n, o, n, &err);
    ms_gofr_get(g, &r);
    t_ok(n == 216 && rc == 0 && r.nbins == nbins, "216 oxygens, %zu bins", r.nbins);
    for (size_t k = 0; k < nref; k++) {
        int b = ref[k].bin;
        t_ok(r.hist[b] == ref[k].hist && rel_near(r.gofr[b], ref[k].g, 1e-6) &&
                 rel_near(r.numint[b], ref[k].numint, 1e-9),
             "rmax %g bin %d: hist %g g %g numint %g", rmax, b, r.hist[b], r.gofr[b], r.numint[b]);
    }
    int zero = 1;
    for (size_t i = hmax; i < r.nbins; i++) zero &= r.hist[i] == 0 && r.gofr[i] == 0;
    t_ok(zero && r.hist[hmax - 1] > 0, "bins from %zu on are not normalised: 0", hmax);
    ms_gofr_free(g);
}

static void test_water_gofr(void)
{
    t_suite = "measure/water";
    ms_molecule *m = load("water648.pdb");
    if (!m) return;
    set_cell(m, 18.774349, 18.774349, 18.774349, 90, 90, 90);
    uint32_t *o = malloc(m->atoms.n * 4);
    size_t n = 0;
    for (size_t i = 0; i < m->atoms.n; i++)
        if (!strcmp(ms_mol_str(m, m->atoms.name[i]), "O")) o[n++] = (uint32_t)i;
    static const gofr_ref near9[] = {
        {25, 4, 0.06974555940220337, 0.018518518518518517},
        {27, 174, 2.6087267554543376, 1.2407407407407407},
        {28, 176, 2.4568066480602115, 2.0555555555555554},
        {30, 122, 1.4870098118981772, 3.3518518518518516},
        {45, 200, 1.0954241377692633, 12.38888888888889},
        {60, 302, 0.9355756099375477, 29.74074074074074},
        {89, 740, 1.0475474796235833, 98.94444444444444}};
    static const gofr_ref far15[] = {
        {93, 750, 0.9730645908375001, 112.52777777777777},
        {100, 732, 1.0245411693348694, 137.13888888888889},
        {120, 462, 1.0704671228394027, 190.77777777777777},
        {132, 198, 1.0199251211273634, 207.6851851851852}};
    check_water(m, o, n, 9.0, 91, 91, near9, MS_COUNTOF(near9));
    check_water(m, o, n, 15.0, 151, 133, far15, MS_COUNTOF(far15));
    free(o);
    ms_mol_free(m);
}

/* Geometry of the first residues of pept.pdb (MDAnalysis calc_bonds/angles/dihedrals). */
static void test_pept_geometry(void)
{
    t_suite = "measure/pept";
    ms_molecule *m = load("pept.pdb");
    if (!m) return;
    double p[15][3];
    for (int i = 0; i < 15; i++)
        for (int k = 0; k < 3; k++) p[i][k] = m->frames[0].pos[3 * i + k];
    double d[3];
    ms_v3_sub(p[1], p[0], d);
    t_ok(near(ms_v3_length(d), 1.4902863167400682, 1e-5), "N-CA bond length");
    double u[3], v[3];
    ms_v3_sub(p[0], p[1], u), ms_v3_sub(p[6], p[1], v);
    t_ok(near(ms_v3_angle(u, v), 106.38191442875761, 1e-4), "N-CA-C angle");
    t_ok(near(ms_v3_dihedral(p[0], p[1], p[6], p[8]), 172.50552192794018, 1e-4), "psi of residue 1");
    t_ok(near(ms_v3_dihedral(p[6], p[8], p[9], p[12]), -124.16306630441241, 1e-4), "phi of residue 2");
    ms_mol_free(m);
}

/* Hydrogen bonds of helix_amber.pdb: brute force with the same rules in measure_refs.py. */
static void test_helix_hbonds(void)
{
    int rc;
    t_suite = "measure/helix";
    ms_molecule *m = load("helix_amber.pdb");
    if (!m) return;
    uint32_t *all = iota(m->atoms.n);
    ms_atomset s = {m, 0, all, m->atoms.n};
    ms_hbonds h;
    ms_error err = {{0}};
    rc = ms_measure_hbonds(&s, NULL, 3.0, 20, &h, &err);
    t_ok(rc == 0 && h.n == 0, "none at 3.0 A, 20 deg");
    ms_hbonds_free(&h);
    rc = ms_measure_hbonds(&s, NULL, 3.5, 30, &h, &err);
    t_ok(rc == 0 && h.n == 20 && h.donor[0] == 66 &&
             h.acceptor[0] == 15 && h.hydrogen[0] == 67 && h.donor[2] == 91 && h.acceptor[2] == 51,
         "20 at 3.5 A, 30 deg, sorted (%zu)", h.n);
    ms_hbonds_free(&h);
    free(all);
    ms_mol_free(m);
}

int main(void)
{
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    test_matrices();
    test_eigen();
    test_geometry();
    test_tetrahedron();
    test_inertia_box();
    test_fit_rotation();
    test_fit_mirror();
    test_fit_degenerate();
    test_fit_sets();
    test_trajectory();
    test_contacts();
    test_hbonds();
    test_sasa_spheres();
    test_gofr_gas();
    test_gofr_triclinic_brute();
    test_gofr_plain();
    test_1tii();
    test_1tii_pairs();
    test_water_gofr();
    test_pept_geometry();
    test_helix_hbonds();
    ms_registry_free(&reg);
    return t_done();
}
