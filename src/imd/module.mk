# src/imd: the IMD (Interactive Molecular Dynamics) protocol's codec and client connection.
src_libmscore_la_SOURCES += \
	src/imd/imd.h src/imd/imd.c src/imd/imd_net.c
