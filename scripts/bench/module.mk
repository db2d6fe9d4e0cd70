# scripts/bench: benchmark drivers, built and run by `make bench` (not by `make` or the tests).
EXTRA_PROGRAMS += scripts/bench/bench_scene scripts/bench/bench_rt
BENCH_REPLICA = scripts/bench/replica.h scripts/bench/replica.c plugins/pdb.c $(PLUGIN_UTIL)
scripts_bench_bench_scene_SOURCES = scripts/bench/bench_scene.c $(BENCH_REPLICA)
scripts_bench_bench_scene_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS)
scripts_bench_bench_scene_CFLAGS = $(AM_CFLAGS)
scripts_bench_bench_rt_SOURCES = scripts/bench/bench_rt.c $(BENCH_REPLICA)
scripts_bench_bench_rt_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS) -lm
scripts_bench_bench_rt_CFLAGS = $(AM_CFLAGS)
CLEANFILES += scripts/bench/bench_scene$(EXEEXT) scripts/bench/bench_rt$(EXEEXT)

bench-scene: scripts/bench/bench_scene$(EXEEXT)
	scripts/bench/bench_scene $(top_srcdir)/tests/data

bench: bench-scene
.PHONY: bench bench-scene
