/* builtin/psf.c: the PSF plugin under its own entry name (ms_plugin_entry_psf), so that one
 * program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_psf
#include "../psf.c"
