# tests/fuzz: a fuzz target for every file reader (fuzz_<format>.c: LLVMFuzzerTestOneInput)
# and for the selection parser and the IMD message decoder.
#
# Smoke drivers, run by tests/run-tests over tests/fuzz/corpus/<format>: each target with
# driver.c (seeds plus deterministic mutations), its plugin and the loading core, compiled
# with AddressSanitizer and UBSan when the compiler has them. `make fuzz` builds real
# libFuzzer binaries tests/fuzz/lf_<format> with clang instead; run one with a scratch corpus
# folder first (new inputs go there) and the seeds second, e.g.
#   mkdir -p /tmp/c && tests/fuzz/lf_dcd -max_total_time=60 /tmp/c tests/fuzz/corpus/dcd
# tests/fuzz-run builds them and runs every one for FUZZ_SECONDS on a copy of its corpus.
FUZZ_FORMATS = pdb psf dcd xyz gro dx ccp4 cube xtc trr cif pqr mol2 namdbin poscar xdatcar cor \
	js parm7 rst7 crd crdbox lammpsdata lammpstrj
if HAVE_SQLITE3
FUZZ_FORMATS += dms
endif
if HAVE_NETCDF
FUZZ_FORMATS += netcdf
endif
FUZZ_CORE = \
	src/base/base.c src/base/strtab.c src/base/threads.c src/base/bitset.c \
	src/base/safewrite.c src/base/grid.c \
	src/molecule/molecule.c src/molecule/volume.c src/molecule/elements.c \
	src/molecule/bonds.c src/molecule/classify.c src/molecule/molset.c \
	src/fileio/registry.c src/fileio/load.c src/fileio/assembly.c src/fileio/write.c
check_LTLIBRARIES = tests/fuzz/libfuzzcore.la
tests_fuzz_libfuzzcore_la_SOURCES = $(FUZZ_CORE) plugins/plugin_util.c plugins/cif_tok.c
tests_fuzz_libfuzzcore_la_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)

FUZZ_SMOKE = $(FUZZ_FORMATS:%=tests/fuzz/fuzz_%$(EXEEXT))
tests/fuzz/fuzz_%$(EXEEXT): $(srcdir)/tests/fuzz/fuzz_%.c $(srcdir)/plugins/%.c \
		$(srcdir)/tests/fuzz/fuzz.h $(srcdir)/tests/fuzz/driver.c tests/fuzz/libfuzzcore.la
	$(AM_V_CCLD)$(LIBTOOL) $(AM_V_lt) --tag=CC --mode=link $(CC) $(DEFS) $(DEFAULT_INCLUDES) \
		$(AM_CPPFLAGS) $(CPPFLAGS) $(AM_CFLAGS) $(CFLAGS) $(SAN_CFLAGS) $(NETCDF_CFLAGS) \
		$(LDFLAGS) -o $@ \
		$(srcdir)/tests/fuzz/fuzz_$*.c $(srcdir)/plugins/$*.c $(srcdir)/tests/fuzz/driver.c \
		tests/fuzz/libfuzzcore.la $(SQLITE3_LIBS) $(PTHREAD_LIBS) $(NETCDF_LIBS) -lm
CLEANFILES += $(FUZZ_SMOKE)
EXTRA_DIST += tests/fuzz/fuzz.h tests/fuzz/driver.c $(FUZZ_FORMATS:%=tests/fuzz/fuzz_%.c)

# The selection parser's target: the selection core with sanitizers over the fuzz core, run
# by its own smoke driver (select_driver.c) over tests/fuzz/corpus/select.
# The IMD message decoder's target: the codec over the fuzz core (base), run by driver.c over
# tests/fuzz/corpus/imd (seeds from tests/fuzz/make_imd_corpus.py).
check_PROGRAMS += tests/fuzz/fuzz_select
tests_fuzz_fuzz_select_SOURCES = tests/fuzz/fuzz_select.c tests/fuzz/select_driver.c \
	$(SELECT_CORE_SOURCES) $(SS_CORE_SOURCES)
tests_fuzz_fuzz_select_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_select_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_select_LDADD = tests/fuzz/libfuzzcore.la $(PTHREAD_LIBS) -lm
check_PROGRAMS += tests/fuzz/fuzz_imd
tests_fuzz_fuzz_imd_SOURCES = tests/fuzz/fuzz_imd.c tests/fuzz/driver.c src/imd/imd.c
tests_fuzz_fuzz_imd_CFLAGS = $(AM_CFLAGS) $(SAN_CFLAGS)
tests_fuzz_fuzz_imd_LDFLAGS = $(SAN_CFLAGS)
tests_fuzz_fuzz_imd_LDADD = tests/fuzz/libfuzzcore.la $(PTHREAD_LIBS) -lm
EXTRA_DIST += tests/fuzz/make_imd_corpus.py

LF_FLAGS = -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
LF_CORE = $(FUZZ_CORE:%=$(srcdir)/%) $(srcdir)/plugins/plugin_util.c $(srcdir)/plugins/cif_tok.c
LF_SELECT = $(filter %.c,$(SELECT_CORE_SOURCES:%=$(srcdir)/%) $(SS_CORE_SOURCES:%=$(srcdir)/%))
if HAVE_LIBFUZZER
fuzz: $(FUZZ_FORMATS:%=tests/fuzz/lf_%) tests/fuzz/lf_select tests/fuzz/lf_imd
tests/fuzz/lf_%: $(srcdir)/tests/fuzz/fuzz_%.c $(srcdir)/plugins/%.c $(srcdir)/tests/fuzz/fuzz.h \
		$(LF_CORE)
	$(AM_V_CC)$(CLANG) $(LF_FLAGS) $(DEFS) $(DEFAULT_INCLUDES) $(AM_CPPFLAGS) -std=gnu11 \
		-o $@ $(srcdir)/tests/fuzz/fuzz_$*.c $(srcdir)/plugins/$*.c $(LF_CORE) \
		$(NETCDF_CFLAGS) $(SQLITE3_LIBS) -lpthread $(NETCDF_LIBS) -lm -ldl
tests/fuzz/lf_select: $(srcdir)/tests/fuzz/fuzz_select.c $(LF_SELECT) $(LF_CORE)
	$(AM_V_CC)$(CLANG) $(LF_FLAGS) $(DEFS) $(DEFAULT_INCLUDES) $(AM_CPPFLAGS) -std=gnu11 \
		-o $@ $(srcdir)/tests/fuzz/fuzz_select.c $(LF_SELECT) $(LF_CORE) -lpthread -lm -ldl
tests/fuzz/lf_imd: $(srcdir)/tests/fuzz/fuzz_imd.c $(srcdir)/src/imd/imd.c $(LF_CORE)
	$(AM_V_CC)$(CLANG) $(LF_FLAGS) $(DEFS) $(DEFAULT_INCLUDES) $(AM_CPPFLAGS) -std=gnu11 \
		-o $@ $(srcdir)/tests/fuzz/fuzz_imd.c $(srcdir)/src/imd/imd.c $(LF_CORE) -lpthread -lm -ldl
else
fuzz:
	@echo "make fuzz needs clang with libFuzzer, which configure did not find"; exit 1
endif
CLEANFILES += $(FUZZ_FORMATS:%=tests/fuzz/lf_%) tests/fuzz/lf_select tests/fuzz/lf_imd
.PHONY: fuzz
