/* builtin/netcdf.c: the AMBER NetCDF plugin under its own entry
 * name (ms_plugin_entry_netcdf), so that one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_netcdf
#include "../netcdf.c"
