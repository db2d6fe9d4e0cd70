/* builtin/js.c: the js plugin under its own entry name (ms_plugin_entry_js), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_js
#include "../js.c"
