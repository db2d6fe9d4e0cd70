/* cmd_ss.c: the secondary structure subcommand of `mol`:
 *
 *   mol ssrecalc <molid>      -> ""  (recomputes the structure from the current frame)
 *
 * As in VMD, structure is computed on demand, not per frame: a molecule without HELIX/SHEET
 * records gets it the first time a selection or a representation needs it (ms_ss_ensure),
 * and `mol ssrecalc` recomputes it (replacing the file's records too) from the frame
 * current now. Listeners hear MS_EV_STRUCTURE so cached representations rebuild. */
#include "config.h"
#include "commands/commands.h"
#include "ss/ss.h"

static int mol_ssrecalc(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], "mol ssrecalc");
    if (!m) return TCL_ERROR;
    ms_error err = {{0}};
    if (ms_ss_compute(m, -1, &err))
        return ms_cmd_error(interp, "mol ssrecalc: %s", err.msg);
    ms_molset_emit(&app->mols, MS_EV_STRUCTURE, m, NULL);
    return TCL_OK;
}

void ms_cmd_ss_register(ms_app *app)
{
    static const ms_subcmd table[] = {{"ssrecalc", mol_ssrecalc, 1, 1, "<molid>"},
                                      {NULL, NULL, 0, 0, NULL}};
    ms_cmdset_extend(app, "mol", table);
}
