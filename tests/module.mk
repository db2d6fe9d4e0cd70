# tests: unit tests (C), Tcl-level tests run by molscope, cross-checks, fuzz smoke runs.
# `make check` (or tests/run-tests after `make check-build`) runs them all; the last line
# is "N passed, N failed" (", N skipped" when a backend or peer is missing).
TEST_CORE_LIBS = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS) $(MPI_LIBS)

check_PROGRAMS += tests/unit/test_base tests/unit/test_molecule tests/unit/test_image
tests_unit_test_image_SOURCES = tests/unit/test_image.c tests/unit/ms_test.h
tests_unit_test_image_LDADD = $(TEST_CORE_LIBS)
check_PROGRAMS += tests/unit/test_measure
check_PROGRAMS += tests/unit/test_base tests/unit/test_molecule tests/unit/test_serialize
check_PROGRAMS += tests/unit/test_qsurf
check_PROGRAMS += tests/unit/test_select tests/unit/test_ss
tests_unit_test_ss_SOURCES = tests/unit/test_ss.c tests/unit/ms_test.h plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_ss_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_ss_CFLAGS = $(AM_CFLAGS)
tests_unit_test_base_SOURCES = tests/unit/test_base.c tests/unit/ms_test.h $(PLUGIN_UTIL)
tests_unit_test_base_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_molecule_SOURCES = tests/unit/test_molecule.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_molecule_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_select_SOURCES = tests/unit/test_select.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_select_LDADD = $(TEST_CORE_LIBS)
check_PROGRAMS += tests/unit/test_gl
tests_unit_test_gl_SOURCES = tests/unit/test_gl.c tests/unit/ms_test.h plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_gl_LDADD = $(TEST_CORE_LIBS) -lm
tests_unit_test_gl_CFLAGS = $(AM_CFLAGS)
check_PROGRAMS += tests/unit/test_scene
tests_unit_test_scene_SOURCES = tests/unit/test_scene.c tests/unit/ms_test.h
tests_unit_test_scene_LDADD = $(TEST_CORE_LIBS)
check_PROGRAMS += tests/unit/test_rep
tests_unit_test_rep_SOURCES = tests/unit/test_rep.c tests/unit/ms_test.h
tests_unit_test_rep_LDADD = $(TEST_CORE_LIBS) -lm
tests_unit_test_measure_SOURCES = tests/unit/test_measure.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_measure_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_serialize_SOURCES = tests/unit/test_serialize.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_serialize_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_qsurf_SOURCES = tests/unit/test_qsurf.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_qsurf_LDADD = $(TEST_CORE_LIBS)
# The QuickSurf sources again, built with other mesh storage types.
check_PROGRAMS += tests/unit/test_qsurf_prec
tests_unit_test_qsurf_prec_SOURCES = tests/unit/test_qsurf_prec.c tests/unit/ms_test.h \
	$(QSURF_SOURCES)
tests_unit_test_qsurf_prec_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_qsurf_prec_CFLAGS = $(AM_CFLAGS) -DMS_QSURF_POS_TYPE=double \
	-DMS_QSURF_NORMAL_TYPE=float -DMS_QSURF_COLOR_TYPE=uint16_t

# The QuickSurf benchmark driver (scripts/bench/bench_qsurf.sh runs it).
check_PROGRAMS += tests/tools/qsurfbench
tests_tools_qsurfbench_SOURCES = tests/tools/qsurfbench.c plugins/pdb.c $(PLUGIN_UTIL)
tests_tools_qsurfbench_LDADD = $(TEST_CORE_LIBS)
tests_tools_qsurfbench_CFLAGS = $(AM_CFLAGS)

# Every plugin linked into one program (tests/tools/plugin_*.c rename their entry points).
BUILTIN_PLUGINS = tests/tools/builtin.h tests/tools/plugin_pdb.c tests/tools/plugin_psf.c \
	tests/tools/plugin_dcd.c tests/tools/plugin_xyz.c tests/tools/plugin_gro.c \
	tests/tools/plugin_dx.c tests/tools/plugin_ccp4.c tests/tools/plugin_cube.c \
	tests/tools/plugin_xtc.c tests/tools/plugin_trr.c tests/tools/plugin_pdbx.c \
	plugins/cif_tok.c tests/tools/plugin_pqr.c tests/tools/plugin_mol2.c \
	tests/tools/plugin_namdbin.c $(PLUGIN_UTIL)

check_PROGRAMS += tests/unit/test_formats
tests_unit_test_formats_SOURCES = tests/unit/test_formats.c tests/unit/ms_test.h $(BUILTIN_PLUGINS)
tests_unit_test_formats_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/tests/tools
tests_unit_test_formats_LDADD = $(TEST_CORE_LIBS) -lm

check_PROGRAMS += tests/unit/test_volumes
tests_unit_test_volumes_SOURCES = tests/unit/test_volumes.c tests/unit/ms_test.h $(BUILTIN_PLUGINS)
tests_unit_test_volumes_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/tests/tools
tests_unit_test_volumes_LDADD = $(TEST_CORE_LIBS) -lm

# msdump: loads files like `mol new`/`mol addfile` and prints them as TSV (python cross-checks).
check_PROGRAMS += tests/tools/msdump
tests_tools_msdump_SOURCES = tests/tools/msdump.c $(BUILTIN_PLUGINS)
tests_tools_msdump_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/tests/tools
tests_tools_msdump_LDADD = $(TEST_CORE_LIBS) -lm

# Fuzz smoke drivers: each reader with driver.c, the loader core and the plugin compiled with
# ASan+UBSan (when the compiler has them), run by tests/run-tests over tests/fuzz/corpus/<fmt>.
FUZZ_CORE = \
	src/base/base.c src/base/strtab.c src/base/threads.c src/base/bitset.c \
	src/molecule/molecule.c src/molecule/volume.c src/molecule/elements.c src/molecule/bonds.c \
	src/molecule/classify.c src/molecule/molset.c \
	src/fileio/registry.c src/fileio/load.c src/fileio/assembly.c src/fileio/write.c
FUZZ_FORMATS = pdb psf dcd xyz gro dx ccp4 cube xtc trr cif pqr mol2 namdbin
check_LTLIBRARIES = tests/fuzz/libfuzzcore.la
tests_fuzz_libfuzzcore_la_SOURCES = $(FUZZ_CORE)
tests_fuzz_libfuzzcore_la_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
FUZZ_LIBS = tests/fuzz/libfuzzcore.la $(PTHREAD_LIBS) -lm
check_PROGRAMS += tests/fuzz/fuzz_pdb tests/fuzz/fuzz_psf tests/fuzz/fuzz_dcd \
	tests/fuzz/fuzz_xyz tests/fuzz/fuzz_gro
tests_fuzz_fuzz_pdb_SOURCES = tests/fuzz/fuzz_pdb.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_psf_SOURCES = tests/fuzz/fuzz_psf.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/psf.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_dcd_SOURCES = tests/fuzz/fuzz_dcd.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/dcd.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_xyz_SOURCES = tests/fuzz/fuzz_xyz.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/xyz.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_gro_SOURCES = tests/fuzz/fuzz_gro.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/gro.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_pdb_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_psf_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_dcd_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_xyz_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_gro_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_pdb_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_psf_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_dcd_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_xyz_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_gro_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_pdb_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_psf_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_dcd_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_xyz_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_gro_LDADD = $(FUZZ_LIBS)


# The readers of the second set (volumes, GROMACS, mmCIF, PQR, MOL2, NAMD binary).
check_PROGRAMS += tests/fuzz/fuzz_dx tests/fuzz/fuzz_ccp4 tests/fuzz/fuzz_cube \
	tests/fuzz/fuzz_xtc tests/fuzz/fuzz_trr tests/fuzz/fuzz_cif tests/fuzz/fuzz_pqr \
	tests/fuzz/fuzz_mol2 tests/fuzz/fuzz_namdbin
tests_fuzz_fuzz_dx_SOURCES = tests/fuzz/fuzz_dx.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/dx.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_dx_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_dx_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_dx_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_ccp4_SOURCES = tests/fuzz/fuzz_ccp4.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/ccp4.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_ccp4_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_ccp4_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_ccp4_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_cube_SOURCES = tests/fuzz/fuzz_cube.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/cube.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_cube_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_cube_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_cube_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_xtc_SOURCES = tests/fuzz/fuzz_xtc.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/xtc.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_xtc_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_xtc_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_xtc_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_trr_SOURCES = tests/fuzz/fuzz_trr.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/trr.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_trr_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_trr_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_trr_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_cif_SOURCES = tests/fuzz/fuzz_cif.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/cif.c plugins/cif_tok.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_cif_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_cif_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_cif_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_pqr_SOURCES = tests/fuzz/fuzz_pqr.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/pqr.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_pqr_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_pqr_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_pqr_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_mol2_SOURCES = tests/fuzz/fuzz_mol2.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/mol2.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_mol2_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_mol2_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_mol2_LDADD = $(FUZZ_LIBS)
tests_fuzz_fuzz_namdbin_SOURCES = tests/fuzz/fuzz_namdbin.c tests/fuzz/fuzz.h tests/fuzz/driver.c \
	plugins/namdbin.c $(PLUGIN_UTIL)
tests_fuzz_fuzz_namdbin_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_namdbin_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_namdbin_LDADD = $(FUZZ_LIBS)

# `make fuzz`: real libFuzzer binaries tests/fuzz/lf_<fmt> built by clang. Run one with a
# scratch corpus folder first (new inputs go there) and the seeds second, e.g.
#   mkdir -p /tmp/c && tests/fuzz/lf_dcd -max_total_time=60 /tmp/c tests/fuzz/corpus/dcd
LF_FLAGS = -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
if HAVE_LIBFUZZER
fuzz: $(FUZZ_FORMATS:%=tests/fuzz/lf_%)
LF_CORE = $(FUZZ_CORE:%=$(srcdir)/%) $(srcdir)/plugins/plugin_util.c $(srcdir)/plugins/cif_tok.c
tests/fuzz/lf_%: $(srcdir)/tests/fuzz/fuzz_%.c $(srcdir)/plugins/%.c $(srcdir)/tests/fuzz/fuzz.h \
		$(LF_CORE)
	$(AM_V_CC)$(CLANG) $(LF_FLAGS) $(DEFS) $(DEFAULT_INCLUDES) $(AM_CPPFLAGS) -std=gnu11 \
		-o $@ $(srcdir)/tests/fuzz/fuzz_$*.c $(srcdir)/plugins/$*.c $(LF_CORE) \
		-lpthread -lm -ldl
else
fuzz:
	@echo "make fuzz needs clang with libFuzzer, which configure did not find"; exit 1
endif
CLEANFILES += $(FUZZ_FORMATS:%=tests/fuzz/lf_%)

# The selection parser's fuzz target: the selection core with sanitizers over the fuzz core,
# run by its own smoke driver (select_driver.c) over tests/fuzz/corpus/select.
check_PROGRAMS += tests/fuzz/fuzz_select
tests_fuzz_fuzz_select_SOURCES = tests/fuzz/fuzz_select.c tests/fuzz/select_driver.c \
	$(SELECT_CORE_SOURCES) $(SS_CORE_SOURCES)
tests_fuzz_fuzz_select_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_select_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_select_LDADD = $(FUZZ_LIBS)
if HAVE_LIBFUZZER
fuzz: tests/fuzz/lf_select
LF_SELECT = $(filter %.c,$(SELECT_CORE_SOURCES:%=$(srcdir)/%) $(SS_CORE_SOURCES:%=$(srcdir)/%))
tests/fuzz/lf_select: $(srcdir)/tests/fuzz/fuzz_select.c $(LF_SELECT) $(LF_CORE)
	$(AM_V_CC)$(CLANG) $(LF_FLAGS) $(DEFS) $(DEFAULT_INCLUDES) $(AM_CPPFLAGS) -std=gnu11 \
		-o $@ $(srcdir)/tests/fuzz/fuzz_select.c $(LF_SELECT) $(LF_CORE) -lpthread -lm -ldl
endif
CLEANFILES += tests/fuzz/lf_select

EXTRA_DIST += tests/run-tests tests/tcl tests/data tests/python tests/fuzz/corpus

# The test programs are linked in a second step, after `all` has rebuilt the core library
# (listing both as prerequisites let a parallel make relink them against the old one).
check-build: all
	$(MAKE) $(AM_MAKEFLAGS) $(check_LTLIBRARIES) $(check_PROGRAMS)

check-local: check-build
	$(top_srcdir)/tests/run-tests $(abs_top_builddir)

.PHONY: check-build fuzz

# Per-target flags give the test programs their own objects of the shared plugin sources.
tests_unit_test_base_CFLAGS = $(AM_CFLAGS)
tests_unit_test_molecule_CFLAGS = $(AM_CFLAGS)
tests_unit_test_measure_CFLAGS = $(AM_CFLAGS)
tests_unit_test_serialize_CFLAGS = $(AM_CFLAGS)
tests_unit_test_select_CFLAGS = $(AM_CFLAGS)
tests_unit_test_qsurf_CFLAGS = $(AM_CFLAGS)
