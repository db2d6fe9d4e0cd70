# src/view: display settings, lights, axes, stage and the transform commands' semantics.
src_libmscore_la_SOURCES += \
	src/view/view.h src/view/view.c
