/* plugin_mol2.c: the MOL2 plugin compiled into a test program under its own entry name, so
 * one program can link every plugin. */
#define ms_plugin_entry ms_plugin_entry_mol2
#include "mol2.c"
