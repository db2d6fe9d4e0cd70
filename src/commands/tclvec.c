/* tclvec.c: converting VMD's vectors and 4x4 matrices between Tcl lists and doubles. */
#include "config.h"
#include "commands/commands.h"
#include "commands/tclvec.h"

#include <stdlib.h>

int ms_tcl_get_numlist(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, const char *what,
                       ms_numlist *out)
{
    Tcl_Obj **e;
    int n;
    out->v = out->small;
    out->n = 0;
    if (Tcl_ListObjGetElements(NULL, obj, &n, &e) != TCL_OK)
        return ms_cmd_error(interp, "%s: %s is not a list: '%s'", cmd, what, Tcl_GetString(obj));
    if (n > (int)(sizeof out->small / sizeof *out->small) &&
        !(out->v = ms_alloc_array((size_t)n, sizeof *out->v))) {
        out->v = out->small;
        return ms_cmd_error(interp, "%s: out of memory for %d numbers", cmd, n);
    }
    for (int i = 0; i < n; i++)
        if (Tcl_GetDoubleFromObj(NULL, e[i], &out->v[i]) != TCL_OK) {
            ms_numlist_free(out);
            return ms_cmd_error(interp, "%s: non-numeric in %s: '%s'", cmd, what,
                                Tcl_GetString(e[i]));
        }
    out->n = n;
    return TCL_OK;
}

void ms_numlist_free(ms_numlist *l)
{
    if (l->v != l->small) free(l->v);
    l->v = l->small;
    l->n = 0;
}

int ms_tcl_get_vec3(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, const char *what,
                    double v[3])
{
    ms_numlist l;
    if (ms_tcl_get_numlist(interp, obj, cmd, what, &l) != TCL_OK) return TCL_ERROR;
    int n = l.n;
    for (int k = 0; k < 3 && n == 3; k++) v[k] = l.v[k];
    ms_numlist_free(&l);
    if (n != 3) return ms_cmd_error(interp, "%s: %s must have three elements", cmd, what);
    return TCL_OK;
}

int ms_tcl_get_mat4(Tcl_Interp *interp, Tcl_Obj *obj, const char *cmd, double m[16])
{
    Tcl_Obj **rows, **cols;
    int nr, nc;
    if (Tcl_ListObjGetElements(NULL, obj, &nr, &rows) != TCL_OK)
        return ms_cmd_error(interp, "%s: badly formed matrix: '%s'", cmd, Tcl_GetString(obj));
    if (nr == 1 && Tcl_ListObjGetElements(NULL, rows[0], &nr, &rows) != TCL_OK) nr = 0;
    if (nr != 4) return ms_cmd_error(interp, "%s: need a 4x4 matrix, got '%s'", cmd,
                                     Tcl_GetString(obj));
    for (int r = 0; r < 4; r++) {
        if (Tcl_ListObjGetElements(NULL, rows[r], &nc, &cols) != TCL_OK || nc != 4)
            return ms_cmd_error(interp, "%s: need a 4x4 matrix, row %d is '%s'", cmd, r,
                                Tcl_GetString(rows[r]));
        for (int c = 0; c < 4; c++)
            if (Tcl_GetDoubleFromObj(NULL, cols[c], &m[4 * r + c]) != TCL_OK)
                return ms_cmd_error(interp, "%s: non-numeric in matrix: '%s'", cmd,
                                    Tcl_GetString(cols[c]));
    }
    return TCL_OK;
}

Tcl_Obj *ms_tcl_new_doubles(const double *v, int n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < n; i++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewDoubleObj(v[i]));
    return l;
}

Tcl_Obj *ms_tcl_new_mat4(const double m[16])
{
    Tcl_Obj *rows[4];
    for (int r = 0; r < 4; r++) rows[r] = ms_tcl_new_doubles(m + 4 * r, 4);
    return Tcl_NewListObj(4, rows);
}
