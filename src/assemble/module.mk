# src/assemble: from the application's state to the Scene a device draws: the world (the
# molecules with their reps and user graphics, colours, materials, the view, display size),
# the view's settings and transforms, assembling the scene, the render devices' table, their
# settings and the `render` entry point.
src_libmscore_la_SOURCES += \
	src/assemble/world.h src/assemble/world.c src/assemble/build.c \
	src/assemble/view.h src/assemble/view.c \
	src/assemble/labels.h src/assemble/labels.c \
	src/assemble/devices.h src/assemble/devices.c
