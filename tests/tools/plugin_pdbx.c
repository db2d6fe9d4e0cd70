/* plugin_pdbx.c: the PDBx/mmCIF plugin compiled into a test program under its own entry
 * name, so one program can link every plugin. */
#define ms_plugin_entry ms_plugin_entry_pdbx
#include "cif.c"
