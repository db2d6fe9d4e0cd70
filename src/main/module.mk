# src/main: the program: MPI start-up, the command line, the application with every command
# set (app/app.h, commands/commands.h), VMD's startup order and the shell. Everything else is
# in libmscore, which the tests link too.
bin_PROGRAMS += src/molscope
src_molscope_SOURCES = src/main/main.c
src_molscope_LDADD = src/libmscore.la $(TCL_LIBS) $(PNG_LIBS) $(PTHREAD_LIBS) $(MPI_LIBS)
src_molscope_LDFLAGS = -no-install
