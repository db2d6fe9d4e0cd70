/* atomsel.h: atom selection objects, the `atomselect` Tcl command and its per-object
 * commands (atomselectN num/list/get/set/...). Other commands that take a selection
 * (measure, animate write ... sel, mol fromsels) look objects up here. */
#ifndef MS_ATOMSEL_H
#define MS_ATOMSEL_H

#include <tcl.h>

#include "app/app.h"
#include "select/select.h"

typedef struct ms_atomsel {
    char name[32];       /* the Tcl command: atomselectN */
    int molid;
    long frame;          /* a frame number, or -1 for "now" (the molecule's current frame),
                            -2 for "last" */
    ms_selexpr *expr;
    ms_bitset bits;      /* the atoms selected when last evaluated */
    size_t count;
    uint32_t *indices;   /* ascending, count long (kept in step with bits) */
} ms_atomsel;

/* Find a selection object by its command name; NULL with an error "<cmd>: no atom selection
 * named '<name>'" (also when its molecule was deleted). A selection whose molecule gained
 * atoms since it was evaluated is evaluated again first, so its indices are current. */
ms_atomsel *ms_atomsel_lookup(ms_app *app, Tcl_Interp *interp, const char *name,
                              const char *cmd);
/* The molecule and resolved frame (-1 when the molecule has no frames) of a selection. */
ms_molecule *ms_atomsel_mol(ms_app *app, const ms_atomsel *s);
long ms_atomsel_frame(ms_app *app, const ms_atomsel *s);

/* A selection object named by a command word, for the commands that take one (`animate write
 * ... sel`, `measure`, `volmap`): TCL_OK with the molecule id, the resolved frame (-1 when the
 * molecule has none) and malloc'd ascending atom indices; TCL_ERROR with a message naming cmd
 * and the word otherwise. */
int ms_atomsel_resolve(ms_app *app, Tcl_Interp *interp, const char *name, const char *cmd,
                       int *molid, long *frame, uint32_t **atoms, size_t *natoms);

/* Register atomselect (and VMD's upproc helper). */
void ms_atomsel_register(ms_app *app);

#endif
