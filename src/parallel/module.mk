# src/parallel: MPI start-up and shutdown, collectives, the dynamic for-loop, broadcast
# loading. Every function works without MPI (one rank).
src_libmscore_la_SOURCES += \
	src/parallel/parallel.h src/parallel/internal.h \
	src/parallel/comm.c src/parallel/sched.c src/parallel/bcastload.c
