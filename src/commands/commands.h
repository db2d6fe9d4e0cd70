/* commands.h: the Tcl command bindings and what they share: the table of command sets,
 * subcommand tables that other command files extend (cmd_rep.c adds `mol addrep` ...),
 * molecule id and molspec parsing, and error messages that name the command and the object.
 *
 * Each binding is thin: parse the arguments, call the core, set the result. */
#ifndef MS_COMMANDS_H
#define MS_COMMANDS_H

#include <tcl.h>

#include "app/app.h"

/* A subcommand: objv[0] is the command, objv[1] the subcommand word. */
typedef int (*ms_subcmd_fn)(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);

typedef struct ms_subcmd {
    const char *name;
    ms_subcmd_fn fn;
} ms_subcmd;

/* A command made of subcommands (mol, molinfo, animate, display, color ...). */
typedef struct ms_cmdset ms_cmdset;

/* Create the Tcl command `name` (and its aliases) dispatching over `table` (ended by a
 * {NULL, NULL} entry). Subcommand words match case-insensitively over 15 characters. */
ms_cmdset *ms_cmdset_create(ms_app *app, const char *name, const ms_subcmd *table);
/* Add subcommands to an existing command (from another module). */
int ms_cmdset_extend(ms_app *app, const char *name, const ms_subcmd *table);
/* Called for words that match no subcommand (molinfo <id> get ...): may be NULL. */
void ms_cmdset_fallback(ms_app *app, const char *name, ms_subcmd_fn fn);
/* Every subcommand of a command bumps app->world.scene_version (the live view follows it) unless
 * it was added by ms_cmdset_extend_quiet (queries) or the whole command is marked quiet
 * (molinfo, measure ...: what they change, they bump themselves). */
int ms_cmdset_extend_quiet(ms_app *app, const char *name, const ms_subcmd *table);
void ms_cmdset_quiet(ms_app *app, const char *name);

/* Set an error message "<fmt...>" and return TCL_ERROR. */
int ms_cmd_error(Tcl_Interp *interp, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* A molecule named by id or "top"; NULL with an error naming cmd and the word. */
ms_molecule *ms_cmd_mol(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, const char *cmd);
/* Molecule ids named by a molspec: ids, all, top, none, active, inactive, displayed/on,
 * off, fixed, free/unfix, joined with | / or :. *out is malloc'd. */
int ms_cmd_molspec(ms_app *app, Tcl_Interp *interp, const char *spec, const char *cmd,
                   int **out, int *n);

/* Parse a non-negative count with an upper bound, naming what it is on error. */
int ms_cmd_get_count(Tcl_Interp *interp, Tcl_Obj *obj, long max, const char *what, long *out);

/* Every command set of this module, in the order ms_app_new creates them (cmdsets.c; ended
 * by NULL). Each entry creates its Tcl commands (or adds subcommands to one made before it).
 * Adding a command is its file cmd_<name>.c and a line in that table. */
extern const ms_app_cmdset_fn ms_command_sets[];
void ms_cmd_mol_register(ms_app *app);
void ms_cmd_molinfo_register(ms_app *app);
void ms_cmd_animate_register(ms_app *app);
void ms_cmd_vmdinfo_register(ms_app *app);
/* The scene-side commands (color, material, display, render, graphics ...): scenecmds.h */
/* measure (cmd_measure.c, with bond/angle/dihed/imprp/inverse from cmd_measure_geom.c) and
 * VMD's vector and matrix commands (cmd_vector.c). */
void ms_cmd_measure_register(ms_app *app);
void ms_cmd_measure_geom_register(ms_app *app);
void ms_cmd_vector_register(ms_app *app);
/* volmap density (cmd_volmap.c): Gaussian density maps on the QuickSurf engine. */
void ms_cmd_volmap_register(ms_app *app);
/* mol ssrecalc (cmd_ss.c): secondary structure recomputed on request. */
void ms_cmd_ss_register(ms_app *app);
/* The C commands under the Tcl movie library (cmd_movie.c): ::molscope::movie::run,
 * frameok, pose, started, ffmpeg. */
void ms_cmd_movie_register(ms_app *app);
/* The rep subcommands of mol (addrep, modstyle, ...) and molinfo's rep keywords
 * (cmd_rep.c). */
void ms_cmd_rep_register(ms_app *app);

/* Shared by mol and animate: load a file as `mol new` (new molecule) or into mol. */
typedef struct ms_load_opts ms_load_opts;
int ms_cmd_load(ms_app *app, Tcl_Interp *interp, const char *cmd, const char *path,
                const ms_load_opts *o, ms_molecule *into);
/* Parse VMD's load options (type first last step waitfor filebonds autobonds volsets),
 * and molscope's `bcast on|off` (load on rank 0 and broadcast to every MPI rank: every rank
 * must run the same command at the same point; all frames arrive before the command
 * returns; ignored with one rank or MOLSCOPE_NOBCAST) from objv[start..]; a trailing odd word is returned in *molid_word when allowed. */
int ms_cmd_parse_load_opts(Tcl_Interp *interp, const char *cmd, int objc, Tcl_Obj *const objv[],
                           int start, ms_load_opts *o, Tcl_Obj **molid_word);

#endif
