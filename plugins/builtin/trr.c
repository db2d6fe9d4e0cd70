/* builtin/trr.c: the TRR plugin under its own entry name (ms_plugin_entry_trr), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_trr
#include "../trr.c"
