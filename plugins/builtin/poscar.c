/* builtin/poscar.c: the VASP POSCAR plugin under its own entry name (ms_plugin_entry_poscar), so that
 * one program can link every plugin: see builtin.h. */
#define ms_plugin_entry ms_plugin_entry_poscar
#include "../poscar.c"
