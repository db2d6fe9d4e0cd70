/* builtin/cor.c: the CHARMM coordinate plugin under its own entry name (ms_plugin_entry_cor), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_cor
#include "../cor.c"
