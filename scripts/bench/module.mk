# scripts/bench: benchmark drivers, built and run by `make bench` (not by `make` or the tests).
BENCH_SYSTEM = scripts/bench/bench_system.h scripts/bench/bench_system.c plugins/pdb.c $(PLUGIN_UTIL)
BENCH_LIBS = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)

EXTRA_PROGRAMS += scripts/bench/bench_scene
scripts_bench_bench_scene_SOURCES = scripts/bench/bench_scene.c $(BENCH_SYSTEM)
scripts_bench_bench_scene_LDADD = $(BENCH_LIBS)
scripts_bench_bench_scene_CFLAGS = $(AM_CFLAGS)
CLEANFILES += scripts/bench/bench_scene$(EXEEXT)

bench-scene: scripts/bench/bench_scene$(EXEEXT)
	scripts/bench/bench_scene $(top_srcdir)/tests/data

# render snapshot of 1M-atom VDW and Licorice scenes (scripts/bench/bench_snapshot.sh)
EXTRA_PROGRAMS += scripts/bench/bench_snapshot
scripts_bench_bench_snapshot_SOURCES = scripts/bench/bench_snapshot.c $(BENCH_SYSTEM)
scripts_bench_bench_snapshot_LDADD = $(BENCH_LIBS)
scripts_bench_bench_snapshot_CFLAGS = $(AM_CFLAGS)
CLEANFILES += scripts/bench/bench_snapshot$(EXEEXT)


EXTRA_PROGRAMS += scripts/bench/bench_ss
scripts_bench_bench_ss_SOURCES = scripts/bench/bench_ss.c plugins/pdb.c $(PLUGIN_UTIL)
scripts_bench_bench_ss_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)
scripts_bench_bench_ss_CFLAGS = $(AM_CFLAGS)
CLEANFILES += scripts/bench/bench_ss$(EXEEXT)

bench-ss:
	$(top_srcdir)/scripts/bench/bench_ss.sh

bench: bench-scene bench-ss
.PHONY: bench bench-scene bench-ss
