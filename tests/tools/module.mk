# tests/tools: programs the tests and benchmarks drive.
# msdump loads files as `mol new`/`mol addfile` do and prints them as TSV (python
# cross-checks); qsurfbench times the surface engine (scripts/bench/bench_qsurf.sh).
check_PROGRAMS += tests/tools/msdump tests/tools/qsurfbench
tests_tools_msdump_SOURCES = tests/tools/msdump.c
tests_tools_msdump_LDADD = $(TEST_LIBS)
tests_tools_qsurfbench_SOURCES = tests/tools/qsurfbench.c
tests_tools_qsurfbench_LDADD = $(TEST_LIBS)
