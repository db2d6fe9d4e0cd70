/* molinfo.h: extending `molinfo` with keywords owned by other modules ("rep i",
 * "selection i", numvolumedata ...), and the 4x4 matrix conversions it shares. */
#ifndef MS_MOLINFO_H
#define MS_MOLINFO_H

#include "commands/commands.h"

typedef struct ms_molinfo_keyword {
    const char *name;
    int prefix;   /* matches keywords starting with name ("rep " matches "rep 0") */
    int (*get)(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *keyword,
               long frame, Tcl_Obj **out);
    int (*set)(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *keyword,
               Tcl_Obj *value, long frame);
} ms_molinfo_keyword;

int ms_molinfo_add_keyword(const ms_molinfo_keyword *k);

/* VMD's matrix form {{r0} {r1} {r2} {r3}}, row-major. Reading also accepts it wrapped in a
 * one-element list, as `molinfo get` returns it. */
Tcl_Obj *ms_matrix_to_obj(const float m[16]);
int ms_matrix_from_obj(Tcl_Interp *interp, Tcl_Obj *obj, float m[16], const char *what);
/* The molecule's center, rotate, scale, global and combined view matrices. */
void ms_mol_matrices(const ms_molecule *m, float center[16], float rot[16], float scale[16],
                     float global[16], float view[16]);

#endif
