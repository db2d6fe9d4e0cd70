# src/pbc: periodic boundary conditions, the loops behind pbctools' pbc wrap/unwrap/join (no Tcl here).
src_libmscore_la_SOURCES += \
	src/pbc/pbc.h src/pbc/internal.h src/pbc/cell.c src/pbc/groups.c src/pbc/wrap.c src/pbc/unwrap.c \
	src/pbc/kernels.c
