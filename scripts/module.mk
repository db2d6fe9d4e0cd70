# scripts: set-up, example and benchmark drivers.
EXTRA_DIST += scripts/bootstrap scripts/example scripts/example.tcl \
	scripts/bench/bench_select.sh scripts/bench/bench_select.py \
	scripts/bench/bench_select.tcl scripts/bench/bench_select.sels \
	scripts/bench/replicate_pdb.py
