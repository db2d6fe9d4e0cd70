# src/fileio: plugin registry, loading files into molecules, writing them out.
src_libmscore_la_SOURCES += \
	src/fileio/registry.h src/fileio/registry.c \
	src/fileio/load.h src/fileio/load.c \
	src/fileio/assembly.h src/fileio/assembly.c \
	src/fileio/write.h src/fileio/write.c
pkginclude_HEADERS += plugins/ms_plugin.h
