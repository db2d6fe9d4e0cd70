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
 * (vecdot veccross veclength2 vecinvert vecmul) compute as Tcl's expr would, integers
 * staying integers; the others answer with doubles, as VMD's C versions do. Nothing here
 * changes any state. */
#include "config.h"
#include "commands/commands.h"
#include "commands/tclvec.h"
#include "vecmath/vecmath.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define VEC_CMD(name) static int name(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])

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

/* ---------------------------------------------------------------- Tcl's expr arithmetic */

/* A number as Tcl's expr sees it, for the commands VMD writes in Tcl: an integer stays an
 * integer until a real joins in (or a result would overflow 64 bits, where Tcl would go on
 * with big integers and this goes on with reals). */
typedef struct tnum {
    int is_int;
    Tcl_WideInt i;
    double d;
} tnum;

static tnum tn_int(Tcl_WideInt i) { return (tnum){1, i, (double)i}; }
static tnum tn_real(double d) { return (tnum){0, 0, d}; }

static tnum tn_mul(tnum a, tnum b)
{
    long long r;
    if (a.is_int && b.is_int && !__builtin_mul_overflow((long long)a.i, (long long)b.i, &r))
        return tn_int(r);
    return tn_real(a.d * b.d);
}

static tnum tn_add(tnum a, tnum b)
{
    long long r;
    if (a.is_int && b.is_int && !__builtin_add_overflow((long long)a.i, (long long)b.i, &r))
        return tn_int(r);
    return tn_real(a.d + b.d);
}

static tnum tn_neg(tnum a) { return a.is_int && a.i != LLONG_MIN ? tn_int(-a.i) : tn_real(-a.d); }
static tnum tn_sub(tnum a, tnum b) { return tn_add(a, tn_neg(b)); }
static Tcl_Obj *tn_obj(tnum a) { return a.is_int ? Tcl_NewWideIntObj(a.i) : Tcl_NewDoubleObj(a.d); }

typedef struct tn_list {
    tnum *v;
    int n;
} tn_list;

static int get_tnums(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, const char *what,
                     tn_list *out)
{
    Tcl_Obj **e;
    out->v = NULL;
    if (Tcl_ListObjGetElements(NULL, obj, &out->n, &e) != TCL_OK)
        return ms_cmd_error(interp, "%s: %s is not a list: '%s'", cmd, what, Tcl_GetString(obj));
    if (!(out->v = ms_alloc_array((size_t)out->n, sizeof *out->v)))
        return ms_cmd_error(interp, "%s: out of memory", cmd);
    for (int k = 0; k < out->n; k++) {
        Tcl_WideInt i;
        double d;
        if (Tcl_GetWideIntFromObj(NULL, e[k], &i) == TCL_OK) out->v[k] = tn_int(i);
        else if (Tcl_GetDoubleFromObj(NULL, e[k], &d) == TCL_OK) out->v[k] = tn_real(d);
        else {
            free(out->v);
            out->v = NULL;
            return ms_cmd_error(interp, "%s: non-numeric in %s: '%s'", cmd, what, Tcl_GetString(e[k]));
        }
    }
    return TCL_OK;
}

/* Two expr-style lists; with same_size they must be equally long. */
static int get_tnum_pair(Tcl_Interp *interp, Tcl_Obj *const objv[], const char *cmd,
                         int same_size, tn_list *a, tn_list *b)
{
    if (get_tnums(interp, objv[1], cmd, "first vector", a) != TCL_OK) return TCL_ERROR;
    if (get_tnums(interp, objv[2], cmd, "second vector", b) != TCL_OK) {
        free(a->v);
        return TCL_ERROR;
    }
    if (!same_size || a->n == b->n) return TCL_OK;
    free(a->v);
    free(b->v);
    return ms_cmd_error(interp, "%s: two vectors don't have the same size", cmd);
}

static int set_tnums(Tcl_Interp *interp, const tnum *v, int n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int k = 0; k < n; k++) Tcl_ListObjAppendElement(NULL, l, tn_obj(v[k]));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

/* ---------------------------------------------------------------- vectors */

VEC_CMD(cmd_vecadd)
{
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
    tn_list a, b;
    if (get_tnum_pair(interp, objv, "vecdot", 1, &a, &b) != TCL_OK) return TCL_ERROR;
    tnum sum = tn_int(0);
    for (int k = 0; k < a.n; k++) sum = tn_add(sum, tn_mul(a.v[k], b.v[k]));
    free(a.v);
    free(b.v);
    Tcl_SetObjResult(interp, tn_obj(sum));
    return TCL_OK;
}

VEC_CMD(cmd_veccross)
{
    tn_list a, b;
    if (get_tnum_pair(interp, objv, "veccross", 0, &a, &b) != TCL_OK) return TCL_ERROR;
    int ok = a.n >= 3 && b.n >= 3;
    tnum c[3];
    for (int k = 0; ok && k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        c[k] = tn_sub(tn_mul(a.v[i], b.v[j]), tn_mul(a.v[j], b.v[i]));
    }
    free(a.v);
    free(b.v);
    if (!ok) return ms_cmd_error(interp, "veccross: vectors must have three elements");
    return set_tnums(interp, c, 3);
}

/* One list of numbers as the only argument. */
static int one_vector(Tcl_Interp *interp, Tcl_Obj *const objv[], const char *cmd, ms_numlist *l)
{
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
    if (one_vector(interp, objv, "veclength", &l) != TCL_OK) return TCL_ERROR;
    double s = sum_squares(&l);
    ms_numlist_free(&l);
    return set_double(interp, sqrt(s));
}

VEC_CMD(cmd_veclength2)
{
    tn_list l;
    if (get_tnums(interp, objv[1], "veclength2", "vector", &l) != TCL_OK) return TCL_ERROR;
    tnum sum = tn_int(0);
    for (int k = 0; k < l.n; k++) sum = tn_add(sum, tn_mul(l.v[k], l.v[k]));
    free(l.v);
    Tcl_SetObjResult(interp, tn_obj(sum));
    return TCL_OK;
}

VEC_CMD(cmd_vecnorm)
{
    ms_numlist l;
    if (one_vector(interp, objv, "vecnorm", &l) != TCL_OK) return TCL_ERROR;
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
    if (two_vectors(interp, objv, "vecdist", &a, &b) != TCL_OK) return TCL_ERROR;
    double s = 0.0;
    for (int i = 0; i < a.n; i++) s += (a.v[i] - b.v[i]) * (a.v[i] - b.v[i]);
    ms_numlist_free(&a);
    ms_numlist_free(&b);
    return set_double(interp, sqrt(s));
}

VEC_CMD(cmd_vecinvert)
{
    tn_list l;
    if (get_tnums(interp, objv[1], "vecinvert", "vector", &l) != TCL_OK) return TCL_ERROR;
    for (int k = 0; k < l.n; k++) l.v[k] = tn_neg(l.v[k]);
    set_tnums(interp, l.v, l.n);
    free(l.v);
    return TCL_OK;
}

VEC_CMD(cmd_vecmul)
{
    tn_list a, b;
    if (get_tnum_pair(interp, objv, "vecmul", 1, &a, &b) != TCL_OK) return TCL_ERROR;
    for (int k = 0; k < a.n; k++) a.v[k] = tn_mul(a.v[k], b.v[k]);
    set_tnums(interp, a.v, a.n);
    free(a.v);
    free(b.v);
    return TCL_OK;
}

VEC_CMD(cmd_veczero)
{
    Tcl_Obj *z[3] = {Tcl_NewIntObj(0), Tcl_NewIntObj(0), Tcl_NewIntObj(0)};
    Tcl_SetObjResult(interp, Tcl_NewListObj(3, z));
    return TCL_OK;
}

/* vecsum, vecmean and vecstddev: the sum, the mean, the population standard deviation. */
static int statistic(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                     int which)
{
    ms_numlist l;
    if (one_vector(interp, objv, cmd, &l) != TCL_OK) return TCL_ERROR;
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
    if (ms_tcl_get_mat4(interp, objv[1], "transmult", prod) != TCL_OK) return TCL_ERROR;
    for (int i = 2; i < objc; i++) {
        if (ms_tcl_get_mat4(interp, objv[i], "transmult", m) != TCL_OK) return TCL_ERROR;
        ms_mat4d_mul(prod, m, prod);
    }
    return set_mat4(interp, prod);
}

/* transvec and transvecinv: the rotation taking x onto v, or v onto x. */
static int transvec_cmd(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], const char *cmd,
                        int inverse)
{
    double v[3], m[16];
    if (ms_tcl_get_vec3(interp, objv[1], cmd, "vector", v) != TCL_OK) return TCL_ERROR;
    if (inverse) ms_mat4d_transvecinv(m, v);
    else ms_mat4d_transvec(m, v);
    return set_mat4(interp, m);
}

VEC_CMD(cmd_transvec) { return transvec_cmd(interp, objc, objv, "transvec", 0); }
VEC_CMD(cmd_transvecinv) { return transvec_cmd(interp, objc, objv, "transvecinv", 1); }

VEC_CMD(cmd_transabout)
{
    double axis[3], amount, m[16];
    if (ms_tcl_get_vec3(interp, objv[1], "transabout", "axis", axis) != TCL_OK) return TCL_ERROR;
    static const char *const units[] = {"deg", "rad", "pi", NULL};
    static const double unit_size[] = {M_PI / 180.0, 1.0, M_PI};
    int unit = 0;
    if (ms_arg_double(interp, objv[2], "angle", &amount) ||
        (objc == 4 && ms_arg_choice(interp, objv[3], units, "unit", &unit)))
        return TCL_ERROR;
    amount *= unit_size[unit];
    ms_mat4d_rotate_about(m, axis, amount);
    return set_mat4(interp, m);
}

VEC_CMD(cmd_transidentity)
{
    double m[16];
    ms_mat4d_identity(m);
    return set_mat4(interp, m);
}

/* The elements keep their own values (and string forms), as VMD's Tcl version does. */
VEC_CMD(cmd_transtranspose)
{
    double m[16];
    Tcl_Obj **rows, **cols, *e[16];
    int nr, nc;
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
    if (ms_tcl_get_mat4(interp, objv[1], cmd, m) != TCL_OK ||
        ms_tcl_get_numlist(interp, objv[2], cmd, "vector", &l) != TCL_OK)
        return TCL_ERROR;
    int n = l.n;
    for (int i = 0; i < n && i < 4; i++) v[i] = l.v[i];
    ms_numlist_free(&l);
    if (n != 3 && n != 4) return ms_cmd_error(interp, "%s: vector must be of size 3 or 4", cmd);
    ms_mat4d_apply(m, v, v);
    return set_doubles(interp, v, n);
}

VEC_CMD(cmd_vectrans) { return transform_cmd(interp, objc, objv, "vectrans", 0.0); }
VEC_CMD(cmd_coordtrans) { return transform_cmd(interp, objc, objv, "coordtrans", 1.0); }

void ms_cmd_vector_register(ms_app *app)
{
    static const ms_subcmd cmds[] = {
        {"vecadd", cmd_vecadd, 2, MS_ARGS_ANY, "<vec1> <vec2> ?<vec3> ...?"},
        {"vecsub", cmd_vecsub, 2, 2, "<vec1> <vec2>"},
        {"vecscale", cmd_vecscale, 2, 2, "<scalar> <vector> | <vector> <scalar>"},
        {"vecdot", cmd_vecdot, 2, 2, "<vec1> <vec2>"},
        {"veccross", cmd_veccross, 2, 2, "<vec1> <vec2>"},
        {"veclength", cmd_veclength, 1, 1, "<vector>"},
        {"veclength2", cmd_veclength2, 1, 1, "<vector>"},
        {"vecnorm", cmd_vecnorm, 1, 1, "<vector>"},
        {"vecdist", cmd_vecdist, 2, 2, "<vec1> <vec2>"},
        {"vecinvert", cmd_vecinvert, 1, 1, "<vector>"},
        {"vecmul", cmd_vecmul, 2, 2, "<vec1> <vec2>"},
        {"veczero", cmd_veczero, 0, 0, ""},
        {"vecsum", cmd_vecsum, 1, 1, "<vector>"},
        {"vecmean", cmd_vecmean, 1, 1, "<vector>"},
        {"vecstddev", cmd_vecstddev, 1, 1, "<vector>"},
        {"transmult", cmd_transmult, 2, MS_ARGS_ANY, "<m1> <m2> ?<m3> ...?"},
        {"transvec", cmd_transvec, 1, 1, "<vector>"},
        {"transvecinv", cmd_transvecinv, 1, 1, "<vector>"},
        {"transabout", cmd_transabout, 2, 3, "<axis> <amount> ?deg|rad|pi?"},
        {"transidentity", cmd_transidentity, 0, 0, ""},
        {"transtranspose", cmd_transtranspose, 1, 1, "<matrix>"},
        {"vectrans", cmd_vectrans, 2, 2, "<matrix> <vector>"},
        {"coordtrans", cmd_coordtrans, 2, 2, "<matrix> <vector>"},
    };
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
