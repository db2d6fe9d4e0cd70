/* builtin/xdatcar.c: the VASP XDATCAR plugin under its own entry name (ms_plugin_entry_xdatcar), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_xdatcar
#include "../xdatcar.c"
