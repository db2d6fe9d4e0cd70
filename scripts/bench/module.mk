# scripts/bench: benchmark drivers, built and run by `make bench` (not by `make` or the tests).
EXTRA_PROGRAMS += scripts/bench/bench_scene
scripts_bench_bench_scene_SOURCES = scripts/bench/bench_scene.c plugins/pdb.c $(PLUGIN_UTIL)
scripts_bench_bench_scene_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)
scripts_bench_bench_scene_CFLAGS = $(AM_CFLAGS)
CLEANFILES += scripts/bench/bench_scene$(EXEEXT)

bench-scene: scripts/bench/bench_scene$(EXEEXT)
	scripts/bench/bench_scene $(top_srcdir)/tests/data

EXTRA_PROGRAMS += scripts/bench/bench_ss
scripts_bench_bench_ss_SOURCES = scripts/bench/bench_ss.c plugins/pdb.c $(PLUGIN_UTIL)
scripts_bench_bench_ss_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)
scripts_bench_bench_ss_CFLAGS = $(AM_CFLAGS)
CLEANFILES += scripts/bench/bench_ss$(EXEEXT)

bench-ss:
	$(top_srcdir)/scripts/bench/bench_ss.sh

bench: bench-scene bench-ss
.PHONY: bench bench-scene bench-ss
