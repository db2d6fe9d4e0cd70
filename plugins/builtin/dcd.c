/* builtin/dcd.c: the DCD plugin under its own entry name (ms_plugin_entry_dcd), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_dcd
#include "../dcd.c"
