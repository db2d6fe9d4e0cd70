/* builtin/dms.c: the DMS plugin under its own entry name (ms_plugin_entry_dms), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_dms
#include "../dms.c"
