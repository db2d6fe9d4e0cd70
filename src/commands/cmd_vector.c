/* cmd_vector.c: VMD's vector and matrix commands written in C, the ones analysis scripts
 * call in tight loops (tcl/vectors.tcl defines trans, transaxis, transoffset and friends):
 *
 *   vecadd v1 v2 ?v3 ...?   vecsub v1 v2   vecscale s v | v s   vecdot v1 v2   veccross v1 v2
 *   veclength v   veclength2 v   vecnorm v   vecdist v1 v2   vecinvert v   vecmul v1 v2
 *   veczero   vecsum v   vecmean v   vecstddev v
 *   transmult m1 m2 ?m3 ...?   transvec v   transvecinv v   transabout v angle ?deg|rad|pi?
 *   transidentity   transtranspose m   vectrans m v   coordtrans m v
 *
 * Each returns a number, a list of numbers or a 4x4 matrix. The ones VMD writes in Tcl
 * (vecdot veccross veclength2 vecinvert vecmul) keep integer input integer, as Tcl's expr
 * does; the others answer with doubles, as VMD's C versions do. Nothing here changes any
 * state. */
#include "config.h"
#include "commands/commands.h"
#include "commands/tclvec.h"
#include "vecmath/vecmath.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define VEC_CMD(name) static int name(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])

static int set_doubles(Tcl_Interp *interp, const double *v, int n)
{
    Tcl_SetObjResult(interp, ms_tcl_new_doubles(v, n));
    return TCL_OK;
}

static int set_double(Tcl_Interp *interp, double v)
{
    Tcl_SetObjResult(interp, Tcl_NewDoubleObj(v));
    return TCL_OK;
}

/* Two lists of numbers of the same length. */
static int two_vectors(Tcl_Interp *interp, Tcl_Obj *const objv[], const char *cmd,
                       ms_numlist *a, ms_numlist *b)
{
    if (ms_tcl_get_numlist(interp, objv[1], cmd, "first vector", a) != TCL_OK) return TCL_ERROR;
    if (ms_tcl_get_numlist(interp, objv[2], cmd, "second vector", b) != TCL_OK) {
        ms_numlist_free(a);
        return TCL_ERROR;
    }
    if (a->n == b->n) return TCL_OK;
    ms_numlist_free(a);
    ms_numlist_free(b);
    return ms_cmd_error(interp, "%s: two vectors don't have the same size", cmd);
}

/* ---------------------------------------------------------------- integer-preserving */

/* All elements of a list integers (not 1.0 or 1e3)? Then *out gets them, malloc'd. */
static int int_list(Tcl_Obj *obj, Tcl_WideInt **out, int *n)
{
    Tcl_Obj **e;
    *out = NULL;
    if (Tcl_ListObjGetElements(NULL, obj, n, &e) != TCL_OK) return 0;
    Tcl_WideInt *v = ms_alloc_array((size_t)*n, sizeof *v);
    for (int i = 0; v && i < *n; i++)
        if (Tcl_GetWideIntFromObj(NULL, e[i], &v[i]) != TCL_OK) {
            free(v);
            return 0;
        }
    *out = v;
    return v != NULL;
}

/* Integer sum of x*y (y = x for squares); 0 on overflow, then the caller uses doubles. */
static int int_dot(const Tcl_WideInt *x, const Tcl_WideInt *y, int n, Tcl_WideInt *out)
{
    long long s = 0, p;
    for (int i = 0; i < n; i++) {
        if (__builtin_mul_overflow((long long)x[i], (long long)y[i], &p) ||
            __builtin_add_overflow(s, p, &s))
            return 0;
    }
    *out = s;
    return 1;
}

/* Both arguments integer lists of one length? Then *x and *y hold them (malloc'd). */
static int int_pair(Tcl_Obj *const objv[], Tcl_WideInt **x, Tcl_WideInt **y, int *n)
{
    int n2;
    if (!int_list(objv[1], x, n)) return 0;
    if (!int_list(objv[2], y, &n2) || n2 != *n) {
        free(*x);
        free(*y);
        *x = *y = NULL;
        return 0;
    }
    return 1;
}

/* ---------------------------------------------------------------- vectors */

VEC_CMD(cmd_vecadd)
{
    if (objc < 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "vec1 vec2 ?vec3? ?vec4? ...");
        return TCL_ERROR;
    }
    ms_numlist sum, term;
    if (ms_tcl_get_numlist(interp, objv[1], "vecadd", "vector", &sum) != TCL_OK) return TCL_ERROR;
    for (int t = 2; t < objc; t++) {
        if (ms_tcl_get_numlist(interp, objv[t], "vecadd", "vector", &term) != TCL_OK) {
            ms_numlist_free(&sum);
            return TCL_ERROR;
        }
        int same = term.n == sum.n;
        for (int i = 0; same && i < sum.n; i++) sum.v[i] += term.v[i];
        ms_numlist_free(&term);
        if (!same) {
            ms_numlist_free(&sum);
            return ms_cmd_error(interp, "vecadd: two vectors don't have the same size");
        }
    }
    set_doubles(interp, sum.v, sum.n);
    ms_numlist_free(&sum);
    return TCL_OK;
}

VEC_CMD(cmd_vecsub)
{
    ms_numlist a, b;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "vec1 vec2");
        return TCL_ERROR;
    }
    if (two_vectors(interp, objv, "vecsub", &a, &b) != TCL_OK) return TCL_ERROR;
    for (int i = 0; i < a.n; i++) a.v[i] -= b.v[i];
    set_doubles(interp, a.v, a.n);
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    return TCL_OK;
}

VEC_CMD(cmd_vecscale)
{
    ms_numlist a, b;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "scalar vector | vector scalar");
        return TCL_ERROR;
    }
    if (ms_tcl_get_numlist(interp, objv[1], "vecscale", "first argument", &a) != TCL_OK)
        return TCL_ERROR;
    if (ms_tcl_get_numlist(interp, objv[2], "vecscale", "second argument", &b) != TCL_OK) {
        ms_numlist_free(&a);
        return TCL_ERROR;
    }
    int rc = TCL_OK;
    if (a.n == 0 || b.n == 0) rc = ms_cmd_error(interp, "vecscale: parameters must have data");
    else if (a.n != 1 && b.n != 1)
        rc = ms_cmd_error(interp, "vecscale: one parameter must be a scalar value");
    else {
        ms_numlist *s = a.n == 1 ? &a : &b, *v = a.n == 1 ? &b : &a;
        double k = s->v[0];
        for (int i = 0; i < v->n; i++) v->v[i] *= k;
        set_doubles(interp, v->v, v->n);
    }
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    return rc;
}

VEC_CMD(cmd_vecdot)
{
    ms_numlist a, b;
    Tcl_WideInt *x, *y, s;
    int n;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "vec1 vec2");
        return TCL_ERROR;
    }
    if (int_pair(objv, &x, &y, &n)) {
        int ok = int_dot(x, y, n, &s);
        free(x);
        free(y);
        if (ok) {
            Tcl_SetObjResult(interp, Tcl_NewWideIntObj(s));
            return TCL_OK;
        }
    }
    if (two_vectors(interp, objv, "vecdot", &a, &b) != TCL_OK) return TCL_ERROR;
    double d = 0.0;
    for (int i = 0; i < a.n; i++) d += a.v[i] * b.v[i];
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    return set_double(interp, d);
}

/* The integer cross product; 0 on overflow. */
static int int_cross(const Tcl_WideInt *x, const Tcl_WideInt *y, Tcl_WideInt out[3])
{
    for (int k = 0; k < 3; k++) {
        long long p, q;
        int i = (k + 1) % 3, j = (k + 2) % 3;
        if (__builtin_mul_overflow((long long)x[i], (long long)y[j], &p) ||
            __builtin_mul_overflow((long long)x[j], (long long)y[i], &q) ||
            __builtin_sub_overflow(p, q, &p))
            return 0;
        out[k] = p;
    }
    return 1;
}

VEC_CMD(cmd_veccross)
{
    ms_numlist a, b;
    Tcl_WideInt *x, *y, c[3];
    int n;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "vec1 vec2");
        return TCL_ERROR;
    }
    if (int_pair(objv, &x, &y, &n)) {
        int ok = n >= 3 && int_cross(x, y, c);
        free(x);
        free(y);
        if (ok) {
            Tcl_Obj *e[3] = {Tcl_NewWideIntObj(c[0]), Tcl_NewWideIntObj(c[1]), Tcl_NewWideIntObj(c[2])};
            Tcl_SetObjResult(interp, Tcl_NewListObj(3, e));
            return TCL_OK;
        }
    }
    if (two_vectors(interp, objv, "veccross", &a, &b) != TCL_OK) return TCL_ERROR;
    int ok = a.n >= 3;
    double d[3];
    if (ok) ms_v3_cross(a.v, b.v, d);
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    if (!ok) return ms_cmd_error(interp, "veccross: vectors must have three elements");
    return set_doubles(interp, d, 3);
}

/* One list of numbers as the only argument. */
static int one_vector(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                      ms_numlist *l)
{
    if (objc != 2) {
        Tcl_WrongNumArgs(interp, 1, objv, "vector");
        return TCL_ERROR;
    }
    return ms_tcl_get_numlist(interp, objv[1], cmd, "vector", l);
}

static double sum_squares(const ms_numlist *l)
{
    double s = 0.0;
    for (int i = 0; i < l->n; i++) s += l->v[i] * l->v[i];
    return s;
}

VEC_CMD(cmd_veclength)
{
    ms_numlist l;
    if (one_vector(interp, objc, objv, "veclength", &l) != TCL_OK) return TCL_ERROR;
    double s = sum_squares(&l);
    ms_numlist_free(&l);
    return set_double(interp, sqrt(s));
}

VEC_CMD(cmd_veclength2)
{
    ms_numlist l;
    Tcl_WideInt *x, s;
    int n;
    if (objc == 2 && int_list(objv[1], &x, &n)) {
        int ok = int_dot(x, x, n, &s);
        free(x);
        if (ok) {
            Tcl_SetObjResult(interp, Tcl_NewWideIntObj(s));
            return TCL_OK;
        }
    }
    if (one_vector(interp, objc, objv, "veclength2", &l) != TCL_OK) return TCL_ERROR;
    double d = sum_squares(&l);
    ms_numlist_free(&l);
    return set_double(interp, d);
}

VEC_CMD(cmd_vecnorm)
{
    ms_numlist l;
    if (one_vector(interp, objc, objv, "vecnorm", &l) != TCL_OK) return TCL_ERROR;
    double len = sqrt(sum_squares(&l));
    if (l.n > 0 && len == 0.0) {
        ms_numlist_free(&l);
        return ms_cmd_error(interp, "vecnorm: cannot normalize the zero vector");
    }
    for (int i = 0; i < l.n; i++) l.v[i] /= len;
    set_doubles(interp, l.v, l.n);
    ms_numlist_free(&l);
    return TCL_OK;
}

VEC_CMD(cmd_vecdist)
{
    ms_numlist a, b;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "vec1 vec2");
        return TCL_ERROR;
    }
    if (two_vectors(interp, objv, "vecdist", &a, &b) != TCL_OK) return TCL_ERROR;
    double s = 0.0;
    for (int i = 0; i < a.n; i++) s += (a.v[i] - b.v[i]) * (a.v[i] - b.v[i]);
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    return set_double(interp, sqrt(s));
}

VEC_CMD(cmd_vecinvert)
{
    ms_numlist l;
    Tcl_WideInt *x;
    int n, ok = 1;
    if (objc == 2 && int_list(objv[1], &x, &n)) {
        Tcl_Obj *r = Tcl_NewListObj(0, NULL);
        for (int i = 0; i < n && (ok = x[i] != LLONG_MIN); i++)
            Tcl_ListObjAppendElement(NULL, r, Tcl_NewWideIntObj(-x[i]));
        free(x);
        if (ok) {
            Tcl_SetObjResult(interp, r);
            return TCL_OK;
        }
        Tcl_DecrRefCount(r);
    }
    if (one_vector(interp, objc, objv, "vecinvert", &l) != TCL_OK) return TCL_ERROR;
    for (int i = 0; i < l.n; i++) l.v[i] = -l.v[i];
    set_doubles(interp, l.v, l.n);
    ms_numlist_free(&l);
    return TCL_OK;
}

VEC_CMD(cmd_vecmul)
{
    ms_numlist a, b;
    Tcl_WideInt *x, *y;
    int n, ok = 1;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "vec1 vec2");
        return TCL_ERROR;
    }
    if (int_pair(objv, &x, &y, &n)) {
        Tcl_Obj *r = Tcl_NewListObj(0, NULL);
        long long p;
        for (int i = 0; i < n && (ok = !__builtin_mul_overflow((long long)x[i], (long long)y[i], &p)); i++)
            Tcl_ListObjAppendElement(NULL, r, Tcl_NewWideIntObj(p));
        free(x);
        free(y);
        if (ok) {
            Tcl_SetObjResult(interp, r);
            return TCL_OK;
        }
        Tcl_DecrRefCount(r);
    }
    if (two_vectors(interp, objv, "vecmul", &a, &b) != TCL_OK) return TCL_ERROR;
    for (int i = 0; i < a.n; i++) a.v[i] *= b.v[i];
    set_doubles(interp, a.v, a.n);
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    return TCL_OK;
}

VEC_CMD(cmd_veczero)
{
    if (objc != 1) {
        Tcl_WrongNumArgs(interp, 1, objv, "");
        return TCL_ERROR;
    }
    Tcl_Obj *z[3] = {Tcl_NewIntObj(0), Tcl_NewIntObj(0), Tcl_NewIntObj(0)};
    Tcl_SetObjResult(interp, Tcl_NewListObj(3, z));
    return TCL_OK;
}

/* vecsum, vecmean and vecstddev: the sum, the mean, the population standard deviation. */
static int statistic(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                     int which)
{
    ms_numlist l;
    if (one_vector(interp, objc, objv, cmd, &l) != TCL_OK) return TCL_ERROR;
    double sum = 0.0, var = 0.0;
    for (int i = 0; i < l.n; i++) sum += l.v[i];
    double mean = l.n ? sum / l.n : 0.0;
    for (int i = 0; i < l.n; i++) var += (l.v[i] - mean) * (l.v[i] - mean);
    int n = l.n;
    ms_numlist_free(&l);
    if (which == 0) return set_double(interp, sum);
    if (n == 0) return ms_cmd_error(interp, "%s: the vector is empty", cmd);
    return set_double(interp, which == 1 ? mean : sqrt(var / n));
}

VEC_CMD(cmd_vecsum) { return statistic(interp, objc, objv, "vecsum", 0); }
VEC_CMD(cmd_vecmean) { return statistic(interp, objc, objv, "vecmean", 1); }
VEC_CMD(cmd_vecstddev) { return statistic(interp, objc, objv, "vecstddev", 2); }

/* ---------------------------------------------------------------- matrices */

static int set_mat4(Tcl_Interp *interp, const double m[16])
{
    Tcl_SetObjResult(interp, ms_tcl_new_mat4(m));
    return TCL_OK;
}

VEC_CMD(cmd_transmult)
{
    double prod[16], m[16];
    if (objc < 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "mx my ?m1? ?m2? ...");
        return TCL_ERROR;
    }
    if (ms_tcl_get_mat4(interp, objv[1], "transmult", prod) != TCL_OK) return TCL_ERROR;
    for (int i = 2; i < objc; i++) {
        if (ms_tcl_get_mat4(interp, objv[i], "transmult", m) != TCL_OK) return TCL_ERROR;
        ms_mat4_mul(prod, m, prod);
    }
    return set_mat4(interp, prod);
}

/* transvec and transvecinv: the rotation taking x onto v, or v onto x. */
static int transvec_cmd(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                        int inverse)
{
    double v[3], m[16];
    if (objc != 2) {
        Tcl_WrongNumArgs(interp, 1, objv, "vector");
        return TCL_ERROR;
    }
    if (ms_tcl_get_vec3(interp, objv[1], cmd, "vector", v) != TCL_OK) return TCL_ERROR;
    if (inverse) ms_mat4_transvecinv(m, v);
    else ms_mat4_transvec(m, v);
    return set_mat4(interp, m);
}

VEC_CMD(cmd_transvec) { return transvec_cmd(interp, objc, objv, "transvec", 0); }
VEC_CMD(cmd_transvecinv) { return transvec_cmd(interp, objc, objv, "transvecinv", 1); }

VEC_CMD(cmd_transabout)
{
    double axis[3], amount, m[16];
    if (objc != 3 && objc != 4) {
        Tcl_WrongNumArgs(interp, 1, objv, "axis amount ?deg|rad|pi?");
        return TCL_ERROR;
    }
    if (ms_tcl_get_vec3(interp, objv[1], "transabout", "axis", axis) != TCL_OK) return TCL_ERROR;
    if (Tcl_GetDoubleFromObj(NULL, objv[2], &amount) != TCL_OK)
        return ms_cmd_error(interp, "transabout: non-numeric angle '%s'", Tcl_GetString(objv[2]));
    const char *unit = objc == 4 ? Tcl_GetString(objv[3]) : "deg";
    if (!strcmp(unit, "deg")) amount *= M_PI / 180.0;
    else if (!strcmp(unit, "pi")) amount *= M_PI;
    else if (strcmp(unit, "rad"))
        return ms_cmd_error(interp, "transabout: unit must be deg, rad or pi, not '%s'", unit);
    ms_mat4_rotate_about(m, axis, amount);
    return set_mat4(interp, m);
}

VEC_CMD(cmd_transidentity)
{
    double m[16];
    if (objc != 1) {
        Tcl_WrongNumArgs(interp, 1, objv, "");
        return TCL_ERROR;
    }
    ms_mat4_identity(m);
    return set_mat4(interp, m);
}

/* The elements keep their own values (and string forms), as VMD's Tcl version does. */
VEC_CMD(cmd_transtranspose)
{
    double m[16];
    Tcl_Obj **rows, **cols, *e[16];
    int nr, nc;
    if (objc != 2) {
        Tcl_WrongNumArgs(interp, 1, objv, "matrix");
        return TCL_ERROR;
    }
    if (ms_tcl_get_mat4(interp, objv[1], "transtranspose", m) != TCL_OK) return TCL_ERROR;
    Tcl_ListObjGetElements(NULL, objv[1], &nr, &rows);
    if (nr == 1) Tcl_ListObjGetElements(NULL, rows[0], &nr, &rows);
    for (int r = 0; r < 4; r++) {
        Tcl_ListObjGetElements(NULL, rows[r], &nc, &cols);
        for (int c = 0; c < 4; c++) e[4 * c + r] = cols[c];
    }
    Tcl_Obj *out[4];
    for (int r = 0; r < 4; r++) out[r] = Tcl_NewListObj(4, e + 4 * r);
    Tcl_SetObjResult(interp, Tcl_NewListObj(4, out));
    return TCL_OK;
}

/* vectrans (a 3-vector is a direction: w = 0) and coordtrans (a 3-vector is a point: w = 1);
 * a 4-vector is used as given. The answer has as many elements as the vector. */
static int transform_cmd(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                         double w3)
{
    double m[16], v[4] = {0, 0, 0, w3};
    ms_numlist l;
    if (objc != 3) {
        Tcl_WrongNumArgs(interp, 1, objv, "matrix vector");
        return TCL_ERROR;
    }
    if (ms_tcl_get_mat4(interp, objv[1], cmd, m) != TCL_OK ||
        ms_tcl_get_numlist(interp, objv[2], cmd, "vector", &l) != TCL_OK)
        return TCL_ERROR;
    int n = l.n;
    for (int i = 0; i < n && i < 4; i++) v[i] = l.v[i];
    ms_numlist_free(&l);
    if (n != 3 && n != 4) return ms_cmd_error(interp, "%s: vector must be of size 3 or 4", cmd);
    ms_mat4_apply(m, v, v);
    return set_doubles(interp, v, n);
}

VEC_CMD(cmd_vectrans) { return transform_cmd(interp, objc, objv, "vectrans", 0.0); }
VEC_CMD(cmd_coordtrans) { return transform_cmd(interp, objc, objv, "coordtrans", 1.0); }

void ms_cmd_vector_register(ms_app *app)
{
    static const struct {
        const char *name;
        Tcl_ObjCmdProc *fn;
    } cmds[] = {
        {"vecadd", cmd_vecadd},         {"vecsub", cmd_vecsub},
        {"vecscale", cmd_vecscale},     {"vecdot", cmd_vecdot},
        {"veccross", cmd_veccross},     {"veclength", cmd_veclength},
        {"veclength2", cmd_veclength2}, {"vecnorm", cmd_vecnorm},
        {"vecdist", cmd_vecdist},       {"vecinvert", cmd_vecinvert},
        {"vecmul", cmd_vecmul},         {"veczero", cmd_veczero},
        {"vecsum", cmd_vecsum},         {"vecmean", cmd_vecmean},
        {"vecstddev", cmd_vecstddev},   {"transmult", cmd_transmult},
        {"transvec", cmd_transvec},     {"transvecinv", cmd_transvecinv},
        {"transabout", cmd_transabout}, {"transidentity", cmd_transidentity},
        {"transtranspose", cmd_transtranspose},
        {"vectrans", cmd_vectrans},     {"coordtrans", cmd_coordtrans},
    };
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++)
        Tcl_CreateObjCommand(app->interp, cmds[i].name, cmds[i].fn, app, NULL);
}
