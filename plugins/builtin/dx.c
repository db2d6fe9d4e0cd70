/* builtin/dx.c: the DX plugin under its own entry name (ms_plugin_entry_dx), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_dx
#include "../dx.c"
