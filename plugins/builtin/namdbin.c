/* builtin/namdbin.c: the NAMDBIN plugin under its own entry name (ms_plugin_entry_namdbin), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_namdbin
#include "../namdbin.c"
