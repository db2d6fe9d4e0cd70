# src/vecmath: vectors and 4x4 matrices written once (vec_tmpl.h) for float (vecf.h) and
# double (vecmath.h), 3x3 inverses, VMD's rotations and a symmetric eigen-solver.
src_libmscore_la_SOURCES += \
	src/vecmath/vec_tmpl.h src/vecmath/vecf.h \
	src/vecmath/vecmath.h src/vecmath/vecmath.c src/vecmath/eigen.c
