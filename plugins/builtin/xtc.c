/* builtin/xtc.c: the XTC plugin under its own entry name (ms_plugin_entry_xtc), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_xtc
#include "../xtc.c"
