# src/app: the program: command line, startup, shell.
src_libmscore_la_SOURCES += \
	src/app/app.h src/app/app.c src/app/loading.c \
	src/app/options.h src/app/options.c \
	src/app/shell.h src/app/shell.c

bin_PROGRAMS += src/molscope
src_molscope_SOURCES = src/app/main.c
src_molscope_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS) $(MPI_LIBS)
src_molscope_LDFLAGS = -no-install
