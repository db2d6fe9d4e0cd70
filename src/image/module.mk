# src/image: RGB images and their files (PNG, TGA, PPM, BMP, SGI).
src_libmscore_la_SOURCES += \
	src/image/image.h src/image/image_codecs.h src/image/image.c \
	src/image/png.c src/image/rawformats.c src/image/sgi.c
