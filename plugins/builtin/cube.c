/* builtin/cube.c: the CUBE plugin under its own entry name (ms_plugin_entry_cube), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_cube
#include "../cube.c"
