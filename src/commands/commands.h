/* commands.h: the Tcl command bindings and what they share: the table of command sets,
 * commands made of subcommand tables that other command files extend (cmd_rep.c adds `mol
 * addrep` ...), molecule id and molspec parsing, and the shared file loading. How arguments
 * are declared, counted, read and refused: args.h.
 *
 * Each binding is thin: parse the arguments, call the core, set the result. */
#ifndef MS_COMMANDS_H
#define MS_COMMANDS_H

#include <tcl.h>

#include "app/app.h"
#include "commands/args.h"

/* A command made of subcommands (mol, molinfo, animate, display, color ...), dispatched by
 * the argument layer (args.h). */
typedef struct ms_cmdset ms_cmdset;

/* Create the Tcl command `name` dispatching over `table` (args.h: ended by a NULL name;
 * the table must outlive the command's creation only: it is copied). */
ms_cmdset *ms_cmdset_create(ms_app *app, const char *name, const ms_subcmd *table);
/* Add subcommands to an existing command (from another module). */
int ms_cmdset_extend(ms_app *app, const char *name, const ms_subcmd *table);
/* The entry called for a word that matches no subcommand (molinfo <molid> get ...): its
 * counts include that word, its usage starts with it ("<molid> get|set ..."). */
void ms_cmdset_fallback(ms_app *app, const char *name, const ms_subcmd *entry);
/* Every subcommand of a command bumps app->world.scene_version (the live view follows it) unless
 * it was added by ms_cmdset_extend_quiet (queries) or the whole command is marked quiet
 * (molinfo, measure ...: what they change, they bump themselves). */
int ms_cmdset_extend_quiet(ms_app *app, const char *name, const ms_subcmd *table);
void ms_cmdset_quiet(ms_app *app, const char *name);

/* A command without subcommands (rotate, vecadd ...): spec->name is the command, its counts
 * are of the words after it. spec must live as long as the command. */
void ms_cmd_create(ms_app *app, const ms_subcmd *spec);

/* Frames were appended to m: tell the listeners (vmd_timestep), make the last frame current
 * (vmd_frame) and, when it is the molecule's first, reset the view as VMD does. A Tcl trace
 * callback may delete m meanwhile: 0, or -1 when m is gone (nothing more was done with it). */
int ms_cmd_frames_appended(ms_app *app, ms_molecule *m);
/* A molecule named by id or "top"; NULL with an error naming cmd and the word. */
ms_molecule *ms_cmd_mol(ms_app *app, Tcl_Interp *interp, Tcl_Obj *word, const char *cmd);
/* Molecule ids named by a molspec: ids, all, top, none, active, inactive, displayed/on,
 * off, fixed, free/unfix, joined with | / or :. *out is malloc'd. */
int ms_cmd_molspec(ms_app *app, Tcl_Interp *interp, const char *spec, const char *cmd,
                   int **out, int *n);

/* Every command set of this module, in the order ms_app_new creates them (cmdsets.c; ended
 * by NULL). Each entry creates its Tcl commands (or adds subcommands to one made before it).
 * Adding a command is its file cmd_<name>.c and a line in that table. */
extern const ms_app_cmdset_fn ms_command_sets[];
/* quit and exit (cmd_quit.c) */
void ms_cmd_quit_register(ms_app *app);
/* plugin (cmd_plugin.c) */
void ms_cmd_plugin_register(ms_app *app);
/* imd: a running simulation's coordinates over the IMD protocol (cmd_imd.c) */
void ms_cmd_imd_register(ms_app *app);
/* gettimestep, rawtimestep (cmd_timestep.c) */
void ms_cmd_timestep_register(ms_app *app);
/* play, logfile, vmdcon, sleep, wait (cmd_batch.c) */
void ms_cmd_batch_register(ms_app *app);
/* menu, mouse, tool, user: the interface's commands as VMD answers them with no display
 * (cmd_gui.c) */
void ms_cmd_gui_register(ms_app *app);
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
/* pbc: pbctools' wrap, unwrap, join, set, get (cmd_pbc.c) */
void ms_cmd_pbc_register(ms_app *app);
/* ::molscope::memory (cmd_memory.c): the bytes each data structure holds. */
void ms_cmd_memory_register(ms_app *app);
/* ::molscope::topo (cmd_topo.c, cmd_topo_build.c): the C half of the topotools package. */
void ms_cmd_topo_register(ms_app *app);
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
