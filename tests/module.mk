# tests: unit tests (C), Tcl-level tests run by molscope itself, cross-checks with
# independent programs, fuzz smoke runs. `make check` (or tests/run-tests after `make
# check-build`) runs them all; the last line is "N passed, N failed" (", N skipped" when a
# backend or a peer program is missing). Beside them: tests/sanitize (the unit and Tcl tests
# on an AddressSanitizer + UBSan build of its own) and tests/fuzz-run (every libFuzzer
# target for a fixed time); each ends with the same kind of line.
#
# Test programs link every plugin from plugins/libbuiltin.la (plugins/builtin/builtin.h).
TEST_LIBS = plugins/libbuiltin.la src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS) \
	$(MPI_LIBS) -lm

include tests/unit/module.mk
include tests/tools/module.mk
include tests/fuzz/module.mk

EXTRA_DIST += tests/run-tests tests/fresh-install tests/tcl tests/shell tests/data tests/python tests/pyapi tests/fuzz/corpus \
	tests/sanitize tests/sanitizers tests/fuzz-run

# The test programs are linked in a second step, after `all` has rebuilt the core library
# (listing both as prerequisites let a parallel make relink them against the old one).
check-build: all
	$(MAKE) $(AM_MAKEFLAGS) $(check_LTLIBRARIES) $(check_PROGRAMS) $(FUZZ_SMOKE)

check-local: check-build
	$(top_srcdir)/tests/run-tests $(abs_top_builddir)

.PHONY: check-build

# What the test run leaves: its scratch folder and its log.
clean-local: clean-local-tests
clean-local-tests:
	-rm -rf tests/out tests/test-suite.log
.PHONY: clean-local-tests
