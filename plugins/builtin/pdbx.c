/* builtin/pdbx.c: the PDBx/mmCIF plugin under its own entry name (ms_plugin_entry_pdbx), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_pdbx
#include "../cif.c"
