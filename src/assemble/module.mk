# src/assemble: from the application's state to the Scene a device draws: the render devices'
# table, their per-application settings and the `render` entry point.
src_libmscore_la_SOURCES += \
	src/assemble/devices.h src/assemble/devices.c
