# src/scene: display lists, colours, materials, user graphics and the Scene devices draw.
src_libmscore_la_SOURCES += \
	src/scene/displaylist.h src/scene/displaylist.c \
	src/scene/color.h src/scene/color.c src/scene/colormaps.h src/scene/colormaps.c \
	src/scene/material.h src/scene/material.c \
	src/scene/graphics.h src/scene/graphics.c \
	src/scene/scene.h src/scene/scene.c src/scene/lod.h src/scene/lod.c
