/* builtin/lammpsdata.c: the lammpsdata plugin under its own entry name (ms_plugin_entry_lammpsdata), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_lammpsdata
#include "../lammpsdata.c"
