/* atomsel_int.h: what the atomselect command's files share (atomsel.c: creation, lifetime,
 * dispatch; atomsel_getset.c: get and set; atomsel_methods.c: the other object methods).
 * The public API is atomsel.h. */
#ifndef MS_ATOMSEL_INT_H
#define MS_ATOMSEL_INT_H

#include "commands/atomsel.h"

/* frame values besides frame numbers */
#define MS_ATOMSEL_NOW (-1)
#define MS_ATOMSEL_LAST (-2)

/* A method: objv[0] is the selection's command, objv[1] the method word. */
typedef int (*ms_atomsel_method_fn)(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                                    Tcl_Obj *const objv[]);

/* The molecule of a selection, re-evaluated first when its atom count changed; NULL with an
 * error "<sel> <method>: molecule N was deleted". */
ms_molecule *ms_atomsel_fresh(ms_app *app, Tcl_Interp *interp, ms_atomsel *s,
                              const char *method);
/* Evaluate the selection again on its frame (the `update` method). */
int ms_atomsel_update(ms_app *app, ms_atomsel *s, ms_error *err);
/* Parse a frame word: a number >= 0, first, last or now (the error names the command
 * running, commands/args.h). */
int ms_atomsel_parse_frame(Tcl_Interp *interp, Tcl_Obj *word, long *frame);
/* An error "<sel> <method>: <message>". */
int ms_atomsel_error(Tcl_Interp *interp, const ms_atomsel *s, const char *method,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));

/* Lifetime: the selection's command lives as long as the variable upproc_var_<name> in the
 * frame it was tied to; untie removes the tie in the current frame. */
int ms_atomsel_tie(Tcl_Interp *interp, const char *name);
void ms_atomsel_untie(Tcl_Interp *interp, const char *name);
/* Move the tie from the current frame to frame `level` (as `uplevel` reads it). */
int ms_atomsel_retie(Tcl_Interp *interp, Tcl_Obj *level, const char *name);

/* Methods. */
int ms_atomsel_get(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                   Tcl_Obj *const objv[]);
int ms_atomsel_set(ms_app *app, Tcl_Interp *interp, ms_atomsel *s, int objc,
                   Tcl_Obj *const objv[]);
/* The methods, as a table of the argument layer's kind (commands/args.h). */
extern const struct ms_atomsel_method {
    const char *name;
    ms_atomsel_method_fn fn;
    int min, max;            /* words after the method */
    const char *usage;       /* those words */
    int changes;             /* changes atoms or bonds (and with them what reps draw) */
} ms_atomsel_methods[];

#endif
