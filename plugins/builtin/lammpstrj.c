/* builtin/lammpstrj.c: the lammpstrj plugin under its own entry name (ms_plugin_entry_lammpstrj), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_lammpstrj
#include "../lammpstrj.c"
