#!/usr/bin/env bash
# bench_reps.sh: the representation benchmark: the scene build of VDW, Licorice and
# NewCartoon for 1tii replicated to 1M atoms, through the real rep code (first build and
# rebuild), against the targets VDW <= 0.1 s, Licorice <= 0.3 s, NewCartoon <= 0.5 s.
# Run from a built tree: scripts/bench/bench_reps.sh [--repeat R] [natoms]
# BENCH_METHODS="Bonds Element CPK Element Licorice Element DynamicBonds Element" times the
# bond methods instead; MOLSCOPE=path times another binary (an older build, for a comparison).
set -euo pipefail
cd "$(dirname "$0")/../.."
molscope=${MOLSCOPE:-./src/molscope}
[ -x "$molscope" ] || { echo "bench_reps: build molscope first (make)" >&2; exit 1; }
repeat=5
if [ "${1:-}" = "--repeat" ]; then repeat=$2; shift 2; fi
natoms=${1:-1000000}
mkdir -p bench-out
pdb=bench-out/reps$natoms.pdb
[ -f "$pdb" ] || /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb "$natoms" "$pdb"
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), threads ${MOLSCOPE_THREADS:-all}"
out=$(BENCH_PDB=$pdb BENCH_SRC=tests/data/1tii.pdb BENCH_REPEAT=$repeat MOLSCOPE_TCLLIB=tcl \
      MOLSCOPE_PLUGINDIR=plugins/.libs MOLSCOPE_NOREADLINE=1 \
      "$molscope" -dispdev text -e scripts/bench/bench_reps.tcl < /dev/null)
echo "$out" | awk -F'\t' '
    NF < 3 { next }      # the results -e echoes (VMD does too) are not timing rows
    $1 == "load" { printf "loaded %s in %s s\n", $2, $3; next }
    { t[$1] = $1 == "VDW" ? 0.1 : $1 == "Licorice" ? 0.3 : 0.5
      if (!hdr++) printf "%-11s %11s %26s %26s %8s\n", "method", "primitives", "first build: median/best (CPU)", "rebuild: median/best (CPU)", "target"
      printf "%-11s %11d %9.3f / %.3f (%.2f) s %9.3f / %.3f (%.2f) s %6.1f s  %s\n", $1, $2, $3, $4, $7, $5, $6, $8,
             t[$1], ($3 <= t[$1] ? "met" : "MISSED") }'
