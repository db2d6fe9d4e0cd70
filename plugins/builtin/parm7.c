/* builtin/parm7.c: the AMBER 7 topology plugin under its own entry
 * name (ms_plugin_entry_parm7), so that one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_parm7
#include "../parm7.c"
