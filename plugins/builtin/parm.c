/* builtin/parm.c: the AMBER topology plugin under VMD's older type name under its own entry
 * name (ms_plugin_entry_parm), so that one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_parm
#include "../parm.c"
