# src/molecule: the Molecule data model and structure analysis.
src_libmscore_la_SOURCES += \
	src/molecule/molecule.h src/molecule/molecule.c \
	src/molecule/volume.h src/molecule/volume.c \
	src/molecule/elements.h src/molecule/elements.c \
	src/molecule/analysis.h src/molecule/bonds.c src/molecule/classify.c \
	src/molecule/molset.h src/molecule/molset.c \
	src/molecule/serialize.h src/molecule/serialize.c \
	src/molecule/combine.h src/molecule/combine.c
