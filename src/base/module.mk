# src/base: utilities shared by every module.
src_libmscore_la_SOURCES += \
	src/base/base.h src/base/base.c \
	src/base/strtab.h src/base/strtab.c \
	src/base/threads.h src/base/threads.c \
	src/base/bitset.h src/base/bitset.c \
	src/base/safewrite.h src/base/safewrite.c \
	src/base/grid.h src/base/grid.c
