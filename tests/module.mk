# tests: unit tests (C), Tcl-level tests run by molscope, cross-checks, fuzz smoke runs.
# `make check` (or tests/run-tests after `make check-build`) runs them all; the last line
# is "N passed, N failed" (", N skipped" when a backend or peer is missing).
TEST_CORE_LIBS = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)

check_PROGRAMS += tests/unit/test_base tests/unit/test_molecule tests/unit/test_qsurf
tests_unit_test_base_SOURCES = tests/unit/test_base.c tests/unit/ms_test.h $(PLUGIN_UTIL)
tests_unit_test_base_LDADD = $(TEST_CORE_LIBS)
tests_unit_test_molecule_SOURCES = tests/unit/test_molecule.c tests/unit/ms_test.h \
	plugins/pdb.c $(PLUGIN_UTIL)
tests_unit_test_molecule_LDADD = $(TEST_CORE_LIBS)
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

EXTRA_DIST += tests/run-tests tests/tcl tests/data tests/python

check-build: all $(check_PROGRAMS)

check-local: check-build
	$(top_srcdir)/tests/run-tests $(abs_top_builddir)

.PHONY: check-build

# Per-target flags give the test programs their own objects of the shared plugin sources.
tests_unit_test_base_CFLAGS = $(AM_CFLAGS)
tests_unit_test_molecule_CFLAGS = $(AM_CFLAGS)
tests_unit_test_qsurf_CFLAGS = $(AM_CFLAGS)
