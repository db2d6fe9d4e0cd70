# src/measure: the numbers behind `measure` (no Tcl here).
src_libmscore_la_SOURCES += \
	src/measure/measure.h src/measure/internal.h src/measure/util.c \
	src/measure/basic.c src/measure/fit.c src/measure/traj.c src/measure/pairs.c \
	src/measure/sasa.c src/measure/gofr.c
