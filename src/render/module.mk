# src/render: what a render device is and what the devices share (output files written
# through a temporary name), and the file exporters (Tachyon, POV3, Wavefront, Raster3D,
# RenderMan, STL, VRML-2, X3D). The table of devices is src/assemble/devices.c.
src_libmscore_la_SOURCES += \
	src/render/render.h src/render/render.c \
	src/render/export.h src/render/font.c src/render/tess.c src/render/clip.c \
	src/render/numfmt.c \
	src/render/tachyon.c src/render/pov3.c src/render/wavefront.c \
	src/render/walk.c src/render/r3d.c src/render/rib.c src/render/stl.c src/render/vrml.c
