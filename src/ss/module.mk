# src/ss: secondary structure by DSSP's hydrogen-bond patterns (no Tcl here). The selection
# core uses it, so its fuzz target links these too (SS_CORE_SOURCES).
SS_CORE_SOURCES = src/ss/ss.h src/ss/ssint.h src/ss/ss.c src/ss/hbond.c src/ss/patterns.c
src_libmscore_la_SOURCES += $(SS_CORE_SOURCES)
