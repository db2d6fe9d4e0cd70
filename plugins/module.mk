# plugins: file-format readers and writers, each a module loaded at run time.
PLUGIN_FLAGS = -module -avoid-version -shared
PLUGIN_UTIL = plugins/plugin_util.h plugins/plugin_util.c

plugins_LTLIBRARIES += plugins/pdb.la
plugins_pdb_la_SOURCES = plugins/pdb.c $(PLUGIN_UTIL)
plugins_pdb_la_LDFLAGS = $(PLUGIN_FLAGS)
plugins_pdb_la_LIBADD = -lm
