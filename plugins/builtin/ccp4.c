/* builtin/ccp4.c: the CCP4 plugin under its own entry name (ms_plugin_entry_ccp4), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_ccp4
#include "../ccp4.c"
