/* builtin/rst7.c: the AMBER ASCII restart plugin under its own entry
 * name (ms_plugin_entry_rst7), so that one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_rst7
#include "../rst7.c"
