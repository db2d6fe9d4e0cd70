/* builtin.h: every file-format plugin linked into one program (plugins/libbuiltin.la: each
 * plugin compiled under its own entry name by builtin/<name>.c), for the tests, tools,
 * benchmarks and fuzz drivers that load files without the plugin directory. */
#ifndef MS_PLUGINS_BUILTIN_H
#define MS_PLUGINS_BUILTIN_H

#include "fileio/registry.h"

const ms_plugin *ms_plugin_entry_pdb(void);
const ms_plugin *ms_plugin_entry_psf(void);
const ms_plugin *ms_plugin_entry_dcd(void);
const ms_plugin *ms_plugin_entry_xyz(void);
const ms_plugin *ms_plugin_entry_gro(void);
const ms_plugin *ms_plugin_entry_dx(void);
const ms_plugin *ms_plugin_entry_ccp4(void);
const ms_plugin *ms_plugin_entry_cube(void);
const ms_plugin *ms_plugin_entry_xtc(void);
const ms_plugin *ms_plugin_entry_trr(void);
const ms_plugin *ms_plugin_entry_pdbx(void);
const ms_plugin *ms_plugin_entry_pqr(void);
const ms_plugin *ms_plugin_entry_mol2(void);
const ms_plugin *ms_plugin_entry_namdbin(void);
const ms_plugin *ms_plugin_entry_poscar(void);
const ms_plugin *ms_plugin_entry_xdatcar(void);
const ms_plugin *ms_plugin_entry_cor(void);
const ms_plugin *ms_plugin_entry_js(void);
const ms_plugin *ms_plugin_entry_parm7(void);
const ms_plugin *ms_plugin_entry_parm(void);
const ms_plugin *ms_plugin_entry_rst7(void);
const ms_plugin *ms_plugin_entry_crd(void);
const ms_plugin *ms_plugin_entry_crdbox(void);
const ms_plugin *ms_plugin_entry_lammpsdata(void);
const ms_plugin *ms_plugin_entry_lammpstrj(void);
#ifdef MS_HAVE_SQLITE3
const ms_plugin *ms_plugin_entry_dms(void);
#endif
#ifdef MS_HAVE_NETCDF
const ms_plugin *ms_plugin_entry_netcdf(void);
#endif

/* Add all of them to a registry; 0 or -1 (out of memory). */
static inline int ms_test_add_builtin(ms_registry *r)
{
    const ms_plugin *p[] = {ms_plugin_entry_pdb(), ms_plugin_entry_psf(), ms_plugin_entry_dcd(),
                            ms_plugin_entry_xyz(), ms_plugin_entry_gro(), ms_plugin_entry_dx(),
                            ms_plugin_entry_ccp4(), ms_plugin_entry_cube(), ms_plugin_entry_xtc(),
                            ms_plugin_entry_trr(), ms_plugin_entry_pdbx(), ms_plugin_entry_pqr(),
                            ms_plugin_entry_mol2(), ms_plugin_entry_namdbin(),
                            ms_plugin_entry_poscar(), ms_plugin_entry_xdatcar(),
                            ms_plugin_entry_cor(), ms_plugin_entry_js(),
                            ms_plugin_entry_parm7(), ms_plugin_entry_parm(),
                            ms_plugin_entry_rst7(), ms_plugin_entry_crd(),
                            ms_plugin_entry_crdbox(),
                            ms_plugin_entry_lammpsdata(), ms_plugin_entry_lammpstrj(),
#ifdef MS_HAVE_SQLITE3
                            ms_plugin_entry_dms(),
#endif
#ifdef MS_HAVE_NETCDF
                            ms_plugin_entry_netcdf(),
#endif
    };
    for (size_t i = 0; i < sizeof p / sizeof p[0]; i++)
        if (ms_registry_add(r, p[i], NULL, NULL) < 0) return -1;
    return 0;
}

#endif
