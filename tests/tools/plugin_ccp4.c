/* plugin_ccp4.c: the CCP4 plugin compiled into a test program under its own entry name, so
 * one program can link every plugin. */
#define ms_plugin_entry ms_plugin_entry_ccp4
#include "ccp4.c"
