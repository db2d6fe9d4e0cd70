# src/vecmath: double-precision vectors, 4x4 matrices and a symmetric eigen-solver.
src_libmscore_la_SOURCES += \
	src/vecmath/vecmath.h src/vecmath/vecmath.c src/vecmath/eigen.c
