/* builtin/gro.c: the GRO plugin under its own entry name (ms_plugin_entry_gro), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_gro
#include "../gro.c"
