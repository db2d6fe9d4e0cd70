# src/select: the atom selection language: lexer, parser, macros, evaluation into bit sets
# (no Tcl here; the atomselect command is in src/commands).
SELECT_CORE_SOURCES = \
	src/select/select.h src/select/selint.h \
	src/select/lexer.c src/select/parser.c src/select/macros.c src/select/regex.c \
	src/select/keywords.c src/select/derived.c src/select/access.c \
	src/select/eval.c src/select/compare.c src/select/grid.c src/select/relations.c
src_libmscore_la_SOURCES += $(SELECT_CORE_SOURCES)
