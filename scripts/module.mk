# scripts: set-up, example and benchmark drivers.
EXTRA_DIST += scripts/bootstrap scripts/example scripts/example.tcl
EXTRA_DIST += scripts/bench/replicate.py scripts/bench/bench_qsurf.sh \
	scripts/bench/pymol_gaussian.py
