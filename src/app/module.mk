# src/app: the application's state (ms_app: the interpreter, molecules, plugins, world), the
# command line and the shell. The program itself is src/main.
src_libmscore_la_SOURCES += \
	src/app/app.h src/app/app.c src/app/loading.c \
	src/app/options.h src/app/options.c \
	src/app/shell.h src/app/shell.c src/app/script.c
