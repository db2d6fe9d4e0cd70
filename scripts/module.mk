# scripts: set-up, example and benchmark drivers.
EXTRA_DIST += scripts/bootstrap scripts/example scripts/example.tcl scripts/bench/bcast_load.sh
