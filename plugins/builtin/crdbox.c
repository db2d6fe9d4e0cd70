/* builtin/crdbox.c: the AMBER ASCII trajectory plugin with a box under its own entry
 * name (ms_plugin_entry_crdbox), so that one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_crdbox
#include "../crdbox.c"
