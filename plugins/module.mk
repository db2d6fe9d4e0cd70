# plugins: file-format readers and writers, each a module loaded at run time.
PLUGIN_FLAGS = -module -avoid-version -shared
PLUGIN_UTIL = plugins/plugin_util.h plugins/plugin_util.c

plugins_LTLIBRARIES += plugins/pdb.la
plugins_pdb_la_SOURCES = plugins/pdb.c $(PLUGIN_UTIL)
plugins_pdb_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_pdb_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/psf.la
plugins_psf_la_SOURCES = plugins/psf.c $(PLUGIN_UTIL)
plugins_psf_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/dcd.la
plugins_dcd_la_SOURCES = plugins/dcd.c $(PLUGIN_UTIL)
plugins_dcd_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_dcd_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/xyz.la
plugins_xyz_la_SOURCES = plugins/xyz.c $(PLUGIN_UTIL)
plugins_xyz_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/gro.la
plugins_gro_la_SOURCES = plugins/gro.c $(PLUGIN_UTIL)
plugins_gro_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_gro_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/dx.la
plugins_dx_la_SOURCES = plugins/dx.c $(PLUGIN_UTIL)
plugins_dx_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/ccp4.la
plugins_ccp4_la_SOURCES = plugins/ccp4.c $(PLUGIN_UTIL)
plugins_ccp4_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_ccp4_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/cube.la
plugins_cube_la_SOURCES = plugins/cube.c $(PLUGIN_UTIL)
plugins_cube_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_cube_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/xtc.la
plugins_xtc_la_SOURCES = plugins/xtc.c plugins/gmx_util.h $(PLUGIN_UTIL)
plugins_xtc_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_xtc_la_LIBADD = -lm $(PTHREAD_LIBS)

plugins_LTLIBRARIES += plugins/trr.la
plugins_trr_la_SOURCES = plugins/trr.c plugins/gmx_util.h $(PLUGIN_UTIL)
plugins_trr_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_trr_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/pdbx.la
plugins_pdbx_la_SOURCES = plugins/cif.c plugins/cif_tok.h plugins/cif_tok.c $(PLUGIN_UTIL)
plugins_pdbx_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_pdbx_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/pqr.la
plugins_pqr_la_SOURCES = plugins/pqr.c $(PLUGIN_UTIL)
plugins_pqr_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/mol2.la
plugins_mol2_la_SOURCES = plugins/mol2.c $(PLUGIN_UTIL)
plugins_mol2_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/namdbin.la
plugins_namdbin_la_SOURCES = plugins/namdbin.c $(PLUGIN_UTIL)
plugins_namdbin_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/poscar.la
plugins_poscar_la_SOURCES = plugins/poscar.c plugins/vasp_util.h plugins/gmx_util.h $(PLUGIN_UTIL)
plugins_poscar_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_poscar_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/xdatcar.la
plugins_xdatcar_la_SOURCES = plugins/xdatcar.c plugins/vasp_util.h plugins/gmx_util.h $(PLUGIN_UTIL)
plugins_xdatcar_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_xdatcar_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/cor.la
plugins_cor_la_SOURCES = plugins/cor.c $(PLUGIN_UTIL)
plugins_cor_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_cor_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/js.la
plugins_js_la_SOURCES = plugins/js.c $(PLUGIN_UTIL)
plugins_js_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_js_la_LIBADD = -lm

# The DMS plugin needs SQLite (configure: --with-sqlite3); built only when it was found.
if HAVE_SQLITE3
plugins_LTLIBRARIES += plugins/dms.la
plugins_dms_la_SOURCES = plugins/dms.c plugins/gmx_util.h $(PLUGIN_UTIL)
plugins_dms_la_CFLAGS = $(AM_CFLAGS) $(SQLITE3_CFLAGS)
plugins_dms_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_dms_la_LIBADD = $(SQLITE3_LIBS) -lm
endif

plugins_LTLIBRARIES += plugins/parm7.la plugins/parm.la
plugins_parm7_la_SOURCES = plugins/parm7.c $(PLUGIN_UTIL)
plugins_parm7_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_parm7_la_LIBADD = -lm
plugins_parm_la_SOURCES = plugins/parm.c $(PLUGIN_UTIL)
plugins_parm_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_parm_la_LIBADD = -lm
EXTRA_DIST += plugins/parm7.c plugins/crd.c

plugins_LTLIBRARIES += plugins/rst7.la
plugins_rst7_la_SOURCES = plugins/rst7.c $(PLUGIN_UTIL)
plugins_rst7_la_LDFLAGS = $(PLUGIN_FLAGS)

plugins_LTLIBRARIES += plugins/crd.la plugins/crdbox.la
plugins_crd_la_SOURCES = plugins/crd.c $(PLUGIN_UTIL)
plugins_crd_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_crdbox_la_SOURCES = plugins/crdbox.c $(PLUGIN_UTIL)
plugins_crdbox_la_LDFLAGS = $(PLUGIN_FLAGS)

# AMBER NetCDF: only with libnetcdf (configure --with-netcdf).
if HAVE_NETCDF
plugins_LTLIBRARIES += plugins/netcdf.la
plugins_netcdf_la_SOURCES = plugins/netcdf.c
plugins_netcdf_la_CFLAGS = $(AM_CFLAGS) $(NETCDF_CFLAGS)
plugins_netcdf_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_netcdf_la_LIBADD = $(NETCDF_LIBS)
BUILTIN_NETCDF = plugins/builtin/netcdf.c
endif

plugins_LTLIBRARIES += plugins/lammpsdata.la
plugins_lammpsdata_la_SOURCES = plugins/lammpsdata.c plugins/lammps_util.h $(PLUGIN_UTIL)
plugins_lammpsdata_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_lammpsdata_la_LIBADD = -lm

plugins_LTLIBRARIES += plugins/lammpstrj.la
plugins_lammpstrj_la_SOURCES = plugins/lammpstrj.c plugins/lammps_util.h $(PLUGIN_UTIL)
plugins_lammpstrj_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_lammpstrj_la_LIBADD = -lm

# Every plugin in one convenience library, each under its own entry name (plugins/builtin/),
# for the programs that read files without the plugin directory: tests, tools, benchmarks.
noinst_LTLIBRARIES += plugins/libbuiltin.la
plugins_libbuiltin_la_SOURCES = plugins/builtin/builtin.h \
	plugins/builtin/pdb.c plugins/builtin/psf.c plugins/builtin/dcd.c plugins/builtin/xyz.c \
	plugins/builtin/gro.c plugins/builtin/dx.c plugins/builtin/ccp4.c plugins/builtin/cube.c \
	plugins/builtin/xtc.c plugins/builtin/trr.c plugins/builtin/pdbx.c plugins/builtin/pqr.c \
	plugins/builtin/mol2.c plugins/builtin/namdbin.c plugins/builtin/poscar.c \
	plugins/builtin/xdatcar.c plugins/builtin/cor.c plugins/builtin/js.c \
	plugins/builtin/parm7.c plugins/builtin/parm.c plugins/builtin/rst7.c \
	plugins/builtin/crd.c plugins/builtin/crdbox.c $(BUILTIN_NETCDF) \
	plugins/builtin/lammpsdata.c plugins/builtin/lammpstrj.c plugins/lammps_util.h \
	plugins/cif_tok.c plugins/gmx_util.h plugins/vasp_util.h $(PLUGIN_UTIL)
EXTRA_plugins_libbuiltin_la_SOURCES = plugins/builtin/netcdf.c plugins/builtin/dms.c
plugins_libbuiltin_la_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/plugins/builtin $(NETCDF_CFLAGS)
plugins_libbuiltin_la_LIBADD = $(NETCDF_LIBS)
if HAVE_SQLITE3
plugins_libbuiltin_la_SOURCES += plugins/builtin/dms.c
plugins_libbuiltin_la_CPPFLAGS += $(SQLITE3_CFLAGS)
plugins_libbuiltin_la_LIBADD += $(SQLITE3_LIBS)
endif
