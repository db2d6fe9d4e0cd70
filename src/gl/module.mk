# src/gl: offscreen OpenGL: the OSMesa and EGL back-ends, the GL 3.3 renderer, the display
# device and the `snapshot` render device. Each back-end builds only when configure found it;
# without either, `render snapshot` says so.
src_libmscore_la_SOURCES += src/gl/gl.h src/gl/display.c
if HAVE_GL
src_libmscore_la_SOURCES += \
	src/gl/glfn.h src/gl/glfn.c src/gl/glrender.h src/gl/glrender.c \
	src/gl/shaders.c src/gl/glframe.c src/gl/cull.c \
	src/gl/context.c
else
src_libmscore_la_SOURCES += src/gl/nogl.c
endif
if HAVE_OSMESA
src_libmscore_la_SOURCES += src/gl/ctx_osmesa.c
src_libmscore_la_LIBADD += $(OSMESA_LIBS)
AM_CFLAGS += $(OSMESA_CFLAGS)
endif
if HAVE_EGL
src_libmscore_la_SOURCES += src/gl/ctx_egl.c
src_libmscore_la_LIBADD += $(EGL_LIBS)
AM_CFLAGS += $(EGL_CFLAGS)
endif
