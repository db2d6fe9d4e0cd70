/* tclvec.h: VMD's vectors and 4x4 matrices as Tcl values, shared by the vector commands and
 * `measure`. A matrix is {{r0} {r1} {r2} {r3}}, row-major; reading also accepts it wrapped
 * in a one-element list, as `molinfo get` returns it. Errors name the command. */
#ifndef MS_TCLVEC_H
#define MS_TCLVEC_H

#include <tcl.h>

/* A list of numbers read into doubles; v points at small[] for short lists. */
typedef struct ms_numlist {
    double *v;
    int n;
    double small[16];
} ms_numlist;

/* Read a list of numbers; on error the message is "<cmd>: non-numeric in <what>: '<word>'"
 * (or "<cmd>: <what> is not a list"). Free with ms_numlist_free. */
int ms_tcl_get_numlist(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, const char *what,
                       ms_numlist *out);
void ms_numlist_free(ms_numlist *l);

/* Exactly three numbers ("<cmd>: <what> must have three elements"). */
int ms_tcl_get_vec3(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, const char *what,
                    double v[3]);
int ms_tcl_get_mat4(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, double m[16]);

Tcl_Obj *ms_tcl_new_doubles(const double *v, int n);
Tcl_Obj *ms_tcl_new_mat4(const double m[16]);

#endif
