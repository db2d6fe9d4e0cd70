/* builtin/pqr.c: the PQR plugin under its own entry name (ms_plugin_entry_pqr), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_pqr
#include "../pqr.c"
