/* vec_tmpl.h: the small vector and 4x4 matrix functions, written once for a scalar type and
 * instantiated for float (vecf.h) and double (vecmath.h). The includer defines MS_T (the
 * type), MS_T_SQRT (its square root), MS_VEC(name) and MS_MAT(name) (the names of the
 * 3-vector and matrix functions); this file undefines them. No include guard: it is meant to
 * be included once per type.
 *
 * Matrices are 4x4, row-major, m[4 * row + col], acting on column vectors (p' = M p), which
 * is also how VMD's Tcl matrices {{r0} {r1} {r2} {r3}} and molinfo matrices read. Products
 * and determinants are summed in double whatever the type. */
#include <math.h>
#include <string.h>

/* ---- 3-vectors */
static inline MS_T MS_VEC(dot)(const MS_T a[3], const MS_T b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* out = a - b */
static inline void MS_VEC(sub)(const MS_T a[3], const MS_T b[3], MS_T out[3])
{
    for (int k = 0; k < 3; k++) out[k] = a[k] - b[k];
}

/* out = a x b (out may alias a or b). */
static inline void MS_VEC(cross)(const MS_T a[3], const MS_T b[3], MS_T out[3])
{
    MS_T x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
         z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static inline MS_T MS_VEC(length)(const MS_T a[3]) { return MS_T_SQRT(MS_VEC(dot)(a, a)); }

/* Normalise in place, dividing by the length; a zero vector stays as it is. Returns the
 * old length. */
static inline MS_T MS_VEC(normalize)(MS_T v[3])
{
    MS_T l = MS_VEC(length)(v);
    if (l > 0)
        for (int k = 0; k < 3; k++) v[k] /= l;
    return l;
}

/* The same multiplying by the reciprocal: cheaper, and what the tracers' pictures are made
 * with (the last bit can differ from normalize). */
static inline MS_T MS_VEC(normalize_rcp)(MS_T v[3])
{
    MS_T l = MS_VEC(length)(v);
    if (l > 0) {
        MS_T inv = (MS_T)1 / l;
        for (int k = 0; k < 3; k++) v[k] *= inv;
    }
    return l;
}

/* ---- 4x4 matrices */
static inline void MS_MAT(identity)(MS_T m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1;
}

/* out = a * b (out may alias a or b). */
static inline void MS_MAT(mul)(const MS_T a[16], const MS_T b[16], MS_T out[16])
{
    MS_T t[16];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += (double)a[4 * r + k] * b[4 * k + c];
            t[4 * r + c] = (MS_T)s;
        }
    memcpy(out, t, sizeof t);
}

static inline void MS_MAT(transpose)(const MS_T a[16], MS_T out[16])
{
    MS_T t[16];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) t[4 * c + r] = a[4 * r + c];
    memcpy(out, t, sizeof t);
}

static inline void MS_MAT(translation)(MS_T m[16], MS_T x, MS_T y, MS_T z)
{
    MS_MAT(identity)(m);
    m[3] = x;
    m[7] = y;
    m[11] = z;
}

static inline void MS_MAT(scaling)(MS_T m[16], MS_T s)
{
    MS_MAT(identity)(m);
    m[0] = m[5] = m[10] = s;
}

/* A right-handed rotation by rad radians about the x, y or z axis ('x', 'y', 'z', either
 * case; anything else means z). */
static inline void MS_MAT(axis_rotation)(MS_T m[16], char axis, double rad)
{
    /* The two coordinates that turn, in right-handed order: y->z about x, z->x about y,
     * x->y about z. */
    int x = axis == 'x' || axis == 'X', y = axis == 'y' || axis == 'Y';
    int i = x ? 1 : y ? 2 : 0, j = x ? 2 : y ? 0 : 1;
    MS_T c = (MS_T)cos(rad), s = (MS_T)sin(rad);
    MS_MAT(identity)(m);
    m[4 * i + i] = c;
    m[4 * i + j] = -s;
    m[4 * j + i] = s;
    m[4 * j + j] = c;
}

/* Transform a point (w = 1); only the top three rows of m are read. */
static inline void MS_MAT(point)(const MS_T m[12], const MS_T in[3], MS_T out[3])
{
    MS_T x = in[0], y = in[1], z = in[2];
    for (int r = 0; r < 3; r++)
        out[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3];
}

/* Transform a direction (w = 0), then normalise it (a zero or non-finite length gives
 * zero components where they are finite). */
static inline void MS_MAT(normal)(const MS_T m[16], const MS_T in[3], MS_T out[3])
{
    MS_T x = in[0], y = in[1], z = in[2], v[3];
    for (int r = 0; r < 3; r++) v[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z;
    MS_T len = MS_VEC(length)(v);
    MS_T inv = len > 0 ? (MS_T)1 / len : (MS_T)0;
    for (int r = 0; r < 3; r++) out[r] = v[r] * inv;
}

/* The factor by which m scales lengths (cube root of the 3x3 determinant's magnitude). */
static inline MS_T MS_MAT(scale_factor)(const MS_T m[16])
{
    double det = m[0] * ((double)m[5] * m[10] - (double)m[6] * m[9]) -
                 m[1] * ((double)m[4] * m[10] - (double)m[6] * m[8]) +
                 m[2] * ((double)m[4] * m[9] - (double)m[5] * m[8]);
    return (MS_T)cbrt(fabs(det));
}

#undef MS_T
#undef MS_T_SQRT
#undef MS_VEC
#undef MS_MAT
