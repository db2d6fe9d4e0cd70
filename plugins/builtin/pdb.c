/* builtin/pdb.c: the PDB plugin under its own entry name (ms_plugin_entry_pdb), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_pdb
#include "../pdb.c"
