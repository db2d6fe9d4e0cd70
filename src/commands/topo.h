/* topo.h: what the two files of ::molscope::topo (cmd_topo.c: bonds and terms;
 * cmd_topo_build.c: term and atom guesses, new molecules, LAMMPS data files) share: the
 * selection a subcommand works on, and the handlers of the second file. */
#ifndef MS_CMD_TOPO_H
#define MS_CMD_TOPO_H

#include <stdint.h>
#include <tcl.h>

#include "app/app.h"
#include "commands/args.h"

/* A selection object resolved: its molecule, frame, atoms and a membership byte per atom. */
typedef struct ms_topo_sel {
    ms_molecule *m;
    long frame;
    uint32_t *atoms;
    size_t n;
    uint8_t *in;
} ms_topo_sel;

int ms_topo_sel_open(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, ms_topo_sel *t);
void ms_topo_sel_close(ms_topo_sel *t);

/* Atom types of a bond or term (w atoms) joined by '-', the ends ordered so that a term and
 * its reversal read alike (an improper keeps its order). */
void ms_topo_joined_type(const ms_molecule *m, const uint32_t *at, size_t w, int improper,
                         char *out, size_t cap);
/* Drop the terms of a kind whose atoms are all in the selection; 0 or -1. */
int ms_topo_drop_inside(ms_topo_sel *t, int kind);

int ms_topo_guessterms(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);
int ms_topo_guessatom(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);
int ms_topo_combine(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);
int ms_topo_replicate(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);
int ms_topo_readdata(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);
int ms_topo_writedata(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);

#endif
