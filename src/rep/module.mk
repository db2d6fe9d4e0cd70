# src/rep: representations: rep objects and their cache, style and colouring strings,
# drawframes and smoothing, and the drawing methods (one file each, listed in methods.c).
src_libmscore_la_SOURCES += \
	src/rep/rep.h src/rep/rep_int.h src/rep/rep.c src/rep/update.c src/rep/style.c \
	src/rep/coloring.c src/rep/frames.c src/rep/methods.c src/rep/atoms.c src/rep/pairs.c \
	src/rep/backbone.c src/rep/ribbon.c \
	src/rep/lines.c src/rep/bonds.c src/rep/dynbonds.c src/rep/hbonds.c src/rep/points.c \
	src/rep/vdw.c src/rep/cpk.c src/rep/licorice.c src/rep/trace.c src/rep/tube.c \
	src/rep/newribbons.c src/rep/newcartoon.c src/rep/quicksurf.c src/rep/beads.c \
	src/rep/dotted.c src/rep/polyhedra.c src/rep/volumes.c src/rep/isosurface.c \
	src/rep/volumeslice.c
