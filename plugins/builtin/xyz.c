/* builtin/xyz.c: the XYZ plugin under its own entry name (ms_plugin_entry_xyz), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_xyz
#include "../xyz.c"
