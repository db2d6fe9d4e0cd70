#!/usr/bin/env bash
# bench_twins.sh: issue 17's benchmark (the twins made one): the neighbour searches that
# now share base/grid.h (distance bonds, DynamicBonds, HBonds, within, measure contacts,
# DSSP), QuickSurf and the OpenCL tracer on the shared engine, on 1tii replicated to N atoms
# (bench_twins.tcl says what each step is). With BENCH_BASE naming another built tree (the
# code before the change), the two binaries take turns, twice each, in the same run (each
# figure is the best of all its runs), and the digests of what each step computed are
# compared: same bonds, pairs, selections, structure, pictures.
#   scripts/bench/bench_twins.sh [natoms] [repeats]     (defaults 300000, 3)
#   BENCH_BASE=/path/to/other/tree scripts/bench/bench_twins.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x src/molscope ] || { echo "bench_twins: build molscope first (make)" >&2; exit 1; }
natoms=${1:-300000}
repeat=${2:-3}
mkdir -p bench-out
pdb=bench-out/twins$natoms.pdb
[ -f "$pdb" ] || /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb "$natoms" "$pdb"
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), threads ${MOLSCOPE_THREADS:-all}"

# run TREE LABEL: bench_twins.tcl with TREE's molscope and plugins; lines "LABEL<TAB>..."
run() {
    local out=$PWD/bench-out/twins-$2
    mkdir -p "$out/pocl" "$out/cache"
    BENCH_PDB=$PWD/$pdb BENCH_SRC=$PWD/tests/data/1tii.pdb BENCH_REPEAT=$repeat BENCH_OUT=$out \
        MOLSCOPE_TCLLIB=$1/tcl MOLSCOPE_PLUGINDIR=$1/plugins/.libs MOLSCOPE_NOREADLINE=1 \
        POCL_CACHE_DIR=$out/pocl MOLSCOPE_OPENCL_CACHE=$out/cache \
        "$1/src/molscope" -dispdev text -e scripts/bench/bench_twins.tcl < /dev/null 2>&1 |
        awk -v l="$2" -F'\t' 'NF >= 2 { print l "\t" $0 }'
}

# With a base: base, this tree, base, this tree, so each meets the same machine load
results=""
for round in 1 2; do
    [ -n "${BENCH_BASE:-}" ] && results+=$(run "$BENCH_BASE" base)$'\n'
    results+=$(run "$PWD" new)$'\n'
    [ -n "${BENCH_BASE:-}" ] || break
done
echo "$results" | awk -F'\t' '
    NF < 3 { next }
    $2 == "load" { if (!seen++) print "system: " $3; next }
    { k = $2; if (!(k in order)) { order[k] = ++n; name[n] = k }
      if (!((k, $1) in w) || $3 < w[k, $1]) { w[k, $1] = $3; c[k, $1] = $4 }
      if ((k, $1) in d && d[k, $1] != $5) bad[k] = 1
      d[k, $1] = $5 }
    END {
      printf "%-10s %22s %22s %s\n", "step", "before: wall (CPU) s", "after: wall (CPU) s", "results"
      for (i = 1; i <= n; i++) { k = name[i]
        b = ((k, "base") in w) ? sprintf("%.3f (%.2f)", w[k, "base"], c[k, "base"]) : "-"
        same = !((k, "base") in d) || d[k, "new"] == "-" ? "" : (d[k, "base"] == d[k, "new"] && !bad[k]) ? "same" : "DIFFER"
        printf "%-10s %22s %22s %s\n", k, b, sprintf("%.3f (%.2f)", w[k, "new"], c[k, "new"]), same }
    }'
