# src/live: the live view of the session in a browser (doc/live.md): the scene version it
# follows, rasterized and progressive ray-traced frames rendered at idle, and the web
# server (libmicrohttpd, run from Tcl's event loop). Without libmicrohttpd only a stub is
# built, and `display live on` says why it is unavailable.
src_libmscore_la_SOURCES += src/live/live.h src/live/frames.c
if HAVE_MHD
src_libmscore_la_SOURCES += src/live/server.c src/live/console.c src/live/guard.h \
                           src/live/guard.c
src_libmscore_la_LIBADD += $(MHD_LIBS)
else
src_libmscore_la_SOURCES += src/live/nolive.c
endif
