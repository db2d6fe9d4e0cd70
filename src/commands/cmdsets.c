/* cmdsets.c: the table of command sets ms_app_new creates, in order: quit and exit, the
 * molecule commands, atomselect, the scene-side commands (scenecmds.h), the rep subcommands
 * of mol (which extend `mol`, so they come after it), measure and the vector commands,
 * volmap, the C commands under the movie library, topotools' ::molscope::topo and the
 * memory report ::molscope::memory. */
#include "config.h"
#include "commands/atomsel.h"
#include "commands/commands.h"
#include "commands/scenecmds.h"

#include <stddef.h>

const ms_app_cmdset_fn ms_command_sets[] = {
    ms_cmd_quit_register,
    ms_cmd_batch_register,
    ms_cmd_gui_register,
    ms_cmd_plugin_register,
    ms_cmd_timestep_register,
    ms_cmd_imd_register,
    ms_cmd_mol_register,
    ms_cmd_ss_register,
    ms_cmd_molinfo_register,
    ms_cmd_animate_register,
    ms_cmd_vmdinfo_register,
    ms_atomsel_register,
    ms_cmd_color_register,
    ms_cmd_material_register,
    ms_cmd_display_register,
    ms_cmd_live_register,
    ms_cmd_trans_register,
    ms_cmd_graphics_register,
    ms_cmd_render_register,
    ms_cmd_label_register,
    ms_cmd_state_register,
    ms_cmd_rep_register,
    ms_cmd_vector_register,
    ms_cmd_measure_register,
    ms_cmd_measure_geom_register,
    ms_cmd_volmap_register,
    ms_cmd_movie_register,
    ms_cmd_pbc_register,
    ms_cmd_topo_register,
    ms_cmd_memory_register,
    NULL,
};
