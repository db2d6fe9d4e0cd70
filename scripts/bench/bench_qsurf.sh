#!/usr/bin/env bash
# bench_qsurf.sh: the QuickSurf benchmark. Replicates 1tii to 1M and 4M atoms and times
# molscope's surface at grid spacing 1.0 and 0.5 A (density, marching cubes, triangles,
# bytes per vertex, peak memory added); then, in the same run, PyMOL (Debian's, when
# present) computing a Gaussian map and its isosurface beside molscope on a size PyMOL
# can hold (QSURF_PYMOL_ATOMS, 150k by default), and prints the ratio. Markdown rows for
# doc/BENCHMARKS.md come out at the end.
#
# usage: scripts/bench/bench_qsurf.sh [builddir]
#   QSURF_SIZES="1000000 4000000"  QSURF_SPACINGS="1.0 0.5"  QSURF_PYMOL_ATOMS=150000
#   QSURF_RUNS=2 (best of)  QSURF_BACKEND=cpu|opencl|auto (cpu: auto would add the
#   one-time OpenCL probe, ~0.1 s and ~60 MB with PoCL, to the first run)
#   BENCH_OUT=<folder for the replicated structures and logs>
set -eu
srcdir=$(cd "$(dirname "$0")/../.." && pwd)
builddir=$(cd "${1:-$srcdir}" && pwd)
bench=$builddir/tests/tools/qsurfbench
out=${BENCH_OUT:-$builddir/bench-out/qsurf}
sizes=${QSURF_SIZES:-"1000000 4000000"}
spacings=${QSURF_SPACINGS:-"1.0 0.5"}
pymol_atoms=${QSURF_PYMOL_ATOMS:-150000}
runs=${QSURF_RUNS:-2}
py=/usr/bin/python3
mkdir -p "$out"
[ -x "$bench" ] || { echo "bench_qsurf: build first: make && make check-build" >&2; exit 1; }

structure() {   # replicated 1tii with at least $1 atoms
    local f="$out/1tii_$1.pdb"
    [ -s "$f" ] || "$py" "$srcdir/scripts/bench/replicate.py" "$srcdir/tests/data/1tii.pdb" "$1" "$f" >&2
    echo "$f"
}

field() { sed -n "s/^\(.* \)\{0,1\}$1=\([^ ]*\).*/\2/p" | head -1; }

# The fastest of $runs runs of one configuration: prints its measurement line.
molscope_run() {
    local pdb=$1 h=$2 best="" bt=1e9
    local log="$out/molscope_$(basename "$pdb" .pdb)_h$h.log"
    "$bench" -b "${QSURF_BACKEND:-cpu}" -h "$h" -n "$runs" "$pdb" > "$log" 2>&1 || true
    while read -r line; do
        case "$line" in atoms=*) ;; *) continue;; esac
        t=$(echo "$line" | field total_s)
        if awk "BEGIN{exit !($t < $bt)}"; then bt=$t; best=$line; fi
    done < "$log"
    [ -n "$best" ] || { echo "bench_qsurf: molscope failed, see $log" >&2; tail -3 "$log" >&2; }
    echo "$best"
}

row() {   # markdown row from a measurement line
    local l=$1
    local atoms=$(echo "$l" | field atoms) total=$(echo "$l" | field total_s)
    printf '| molscope QuickSurf | %s | %s | %s | %s | %s | %s | %s (cpu %s) | %s | %s | %.2f | %s MB (%s x target) |\n' \
        "$atoms" "$(echo "$l" | field h)" "$(echo "$l" | field grid)" "$(echo "$l" | field slabs)" \
        "$(echo "$l" | field density_s)" "$(echo "$l" | field mc_s)" "$total" "$(echo "$l" | field cpu_s)" \
        "$(echo "$l" | field triangles)" "$(echo "$l" | field vertex_bytes)" \
        "$(awk "BEGIN{print $total * 1000000 / $atoms}")" \
        "$(echo "$l" | field peak_mb)" "$(echo "$l" | field peak_over_target)"
}

rows=()
echo "== molscope QuickSurf ($(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg))"
for n in $sizes; do
    pdb=$(structure "$n")
    for h in $spacings; do
        line=$(molscope_run "$pdb" "$h")
        echo "$line"
        [ -n "$line" ] && rows+=("$(row "$line")")
    done
done

echo "== beside PyMOL on $pymol_atoms atoms, spacing 1.0"
pdb=$(structure "$pymol_atoms")
line=$(molscope_run "$pdb" 1.0)
echo "$line"
[ -n "$line" ] && rows+=("$(row "$line")")
mtime=$(echo "$line" | field total_s)
if "$py" -c "import pymol" 2>/dev/null; then
    "$py" "$srcdir/scripts/bench/pymol_gaussian.py" "$pdb" 1.0 > "$out/pymol.log" 2>&1 || true
    pl=$(grep '^pymol ' "$out/pymol.log" || true)
    echo "$pl"
    if [ -n "$pl" ]; then
        pt=$(echo "$pl" | field total_s)
        ratio=$(awk "BEGIN{printf \"%.1f\", $pt / $mtime}")
        echo "PyMOL / molscope on $(echo "$pl" | field atoms) atoms: ${ratio}x"
        rows+=("$(printf '| PyMOL map_new gaussian + isosurface | %s | 1.0 | | | %s | %s | %s | | | | %s MB (molscope %sx faster) |' \
            "$(echo "$pl" | field atoms)" "$(echo "$pl" | field map_s)" "$(echo "$pl" | field iso_s)" \
            "$pt" "$(echo "$pl" | field maxrss_mb)" "$ratio")")
    else
        echo "bench_qsurf: PyMOL failed, see $out/pymol.log" >&2
    fi
else
    echo "SKIP: PyMOL is not installed (Debian: python3-pymol)"
fi

echo
echo "| program | atoms | h (A) | grid | slabs | density (s) | MC (s) | total (s) | triangles | bytes/vertex | s per M atoms | peak memory added |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
