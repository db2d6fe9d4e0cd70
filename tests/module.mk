# tests: unit tests (C), Tcl-level tests run by molscope, cross-checks, fuzz smoke runs.
# `make check` (or tests/run-tests after `make check-build`) runs them all; the last line
# is "N passed, N failed" (", N skipped" when a backend or peer is missing).
TEST_CORE_LIBS = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)

check_PROGRAMS += tests/unit/test_base tests/unit/test_molecule tests/unit/test_image
tests_unit_test_image_SOURCES = tests/unit/test_image.c tests/unit/ms_test.h
tests_unit_test_image_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_base_SOURCES = tests/unit/test_base.c tests/unit/ms_test.h $(PLUGIN_UTIL)
tests_unit_test_base_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_molecule_SOURCES = tests/unit/test_molecule.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_molecule_LDADD = $(TEST_CORE_LIBS)
check_PROGRAMS += tests/unit/test_scene
tests_unit_test_scene_SOURCES = tests/unit/test_scene.c tests/unit/ms_test.h
tests_unit_test_scene_LDADD = $(TEST_CORE_LIBS)
check_PROGRAMS += tests/unit/test_rt
tests_unit_test_rt_SOURCES = tests/unit/test_rt.c tests/unit/ms_test.h
tests_unit_test_rt_LDADD = $(TEST_CORE_LIBS) -lm

# Every plugin linked into one program (tests/tools/plugin_*.c rename their entry points).
BUILTIN_PLUGINS = tests/tools/builtin.h tests/tools/plugin_pdb.c tests/tools/plugin_psf.c \
	tests/tools/plugin_dcd.c tests/tools/plugin_xyz.c tests/tools/plugin_gro.c $(PLUGIN_UTIL)

check_PROGRAMS += tests/unit/test_formats
tests_unit_test_formats_SOURCES = tests/unit/test_formats.c tests/unit/ms_test.h $(BUILTIN_PLUGINS)
tests_unit_test_formats_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/tests/tools
tests_unit_test_formats_LDADD = $(TEST_CORE_LIBS) -lm

# msdump: loads files like `mol new`/`mol addfile` and prints them as TSV (python cross-checks).
check_PROGRAMS += tests/tools/msdump
tests_tools_msdump_SOURCES = tests/tools/msdump.c $(BUILTIN_PLUGINS)
tests_tools_msdump_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/tests/tools
tests_tools_msdump_LDADD = $(TEST_CORE_LIBS) -lm

# Fuzz smoke drivers: each reader with driver.c, the loader core and the plugin compiled with
# ASan+UBSan (when the compiler has them), run by tests/run-tests over tests/fuzz/corpus/<fmt>.
FUZZ_CORE = \
	src/base/base.c src/base/strtab.c src/base/threads.c src/base/bitset.c \
	src/molecule/molecule.c src/molecule/elements.c src/molecule/bonds.c \
	src/molecule/classify.c src/molecule/molset.c \
	src/fileio/registry.c src/fileio/load.c src/fileio/write.c
FUZZ_FORMATS = pdb psf dcd xyz gro
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

# `make fuzz`: real libFuzzer binaries tests/fuzz/lf_<fmt> built by clang. Run one with a
# scratch corpus folder first (new inputs go there) and the seeds second, e.g.
#   mkdir -p /tmp/c && tests/fuzz/lf_dcd -max_total_time=60 /tmp/c tests/fuzz/corpus/dcd
LF_FLAGS = -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
if HAVE_LIBFUZZER
fuzz: $(FUZZ_FORMATS:%=tests/fuzz/lf_%)
LF_CORE = $(FUZZ_CORE:%=$(srcdir)/%) $(srcdir)/plugins/plugin_util.c
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

EXTRA_DIST += tests/run-tests tests/tcl tests/data tests/python tests/fuzz/corpus

check-build: all $(check_LTLIBRARIES) $(check_PROGRAMS)

check-local: check-build
	$(top_srcdir)/tests/run-tests $(abs_top_builddir)

.PHONY: check-build fuzz

# Per-target flags give the test programs their own objects of the shared plugin sources.
tests_unit_test_base_CFLAGS = $(AM_CFLAGS)
tests_unit_test_molecule_CFLAGS = $(AM_CFLAGS)
