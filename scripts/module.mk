# scripts: set-up, example and benchmark drivers.
EXTRA_DIST += scripts/bootstrap scripts/example scripts/example.tcl scripts/gpu-check \
	scripts/colormaps.py scripts/live-screenshot.py
EXTRA_DIST += scripts/bench

# `make bench`: every benchmark beside its peer (long; not part of the tests).
bench: all
	@for b in $(top_srcdir)/scripts/bench/bench_*.sh; do echo "### $$b"; bash $$b || exit 1; done
.PHONY: bench
