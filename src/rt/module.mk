# src/rt: TachyonInternal, the photorealistic CPU ray tracer on Embree (doc/rt.md). Without
# Embree only the device, the shared parts and a stub are built, and rendering says why it
# cannot.
# The parts the OpenCL tracer shares (rt_common.h) are built either way.
src_libmscore_la_SOURCES += src/rt/rt.h src/rt/options.c src/rt/tachyon_internal.c \
	src/rt/rt_common.h src/rt/common.c src/rt/camera.c src/rt/strokes.c
if HAVE_EMBREE
src_libmscore_la_SOURCES += \
	src/rt/rt_internal.h src/rt/device.c src/rt/world.c src/rt/place.c src/rt/user.c \
	src/rt/sphere.c src/rt/cylinder.c src/rt/cone.c src/rt/ring.c src/rt/mesh.c \
	src/rt/sample.c src/rt/shade.c src/rt/frame.c src/rt/raydump.c
src_libmscore_la_LIBADD += $(EMBREE_LIBS)
else
src_libmscore_la_SOURCES += src/rt/stub.c
endif
