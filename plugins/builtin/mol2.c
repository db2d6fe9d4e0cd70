/* builtin/mol2.c: the MOL2 plugin under its own entry name (ms_plugin_entry_mol2), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_mol2
#include "../mol2.c"
