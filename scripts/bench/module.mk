# scripts/bench: benchmark drivers, built and run by `make bench` (not by `make` or the tests).
# `make bench` runs every scripts/bench/bench_*.sh (see scripts/module.mk) after building the
# C drivers below.
BENCH_LIBS = plugins/libbuiltin.la src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS) \
	$(MPI_LIBS) -lm
EXTRA_PROGRAMS += scripts/bench/bench_scene scripts/bench/bench_snapshot scripts/bench/bench_ss \
	scripts/bench/bench_rt
BENCH_DRIVERS = scripts/bench/bench_scene$(EXEEXT) scripts/bench/bench_snapshot$(EXEEXT) \
	scripts/bench/bench_ss$(EXEEXT) scripts/bench/bench_rt$(EXEEXT)
CLEANFILES += $(BENCH_DRIVERS)

scripts_bench_bench_scene_SOURCES = scripts/bench/bench_scene.c \
	scripts/bench/bench_system.h scripts/bench/bench_system.c
scripts_bench_bench_scene_LDADD = $(BENCH_LIBS)
scripts_bench_bench_snapshot_SOURCES = scripts/bench/bench_snapshot.c \
	scripts/bench/bench_system.h scripts/bench/bench_system.c
scripts_bench_bench_snapshot_LDADD = $(BENCH_LIBS)
scripts_bench_bench_ss_SOURCES = scripts/bench/bench_ss.c
scripts_bench_bench_ss_LDADD = $(BENCH_LIBS)

bench-programs: $(BENCH_DRIVERS)
bench: bench-programs
.PHONY: bench-programs
scripts_bench_bench_rt_SOURCES = scripts/bench/bench_rt.c \
	scripts/bench/bench_system.h scripts/bench/bench_system.c
scripts_bench_bench_rt_LDADD = $(BENCH_LIBS)

# rt_floor: the rays of a TachyonInternal ray dump traced by Embree alone (bench_rtfloor.sh).
if HAVE_EMBREE
EXTRA_PROGRAMS += scripts/bench/rt_floor
BENCH_DRIVERS += scripts/bench/rt_floor$(EXEEXT)
scripts_bench_rt_floor_SOURCES = scripts/bench/rt_floor.c scripts/bench/rt_floor_own.h \
	scripts/bench/rt_floor_own.c scripts/bench/rt_floor_own8.c scripts/bench/rt_floor_own16.c
scripts_bench_rt_floor_LDADD = $(EMBREE_LIBS) $(PTHREAD_LIBS) -lm
endif
EXTRA_DIST += scripts/bench/rt_floor_own.inc
