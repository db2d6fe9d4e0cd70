/* builtin/crd.c: the AMBER ASCII trajectory plugin under its own entry
 * name (ms_plugin_entry_crd), so that one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_crd
#include "../crd.c"
