# scripts/bench/lib.sh: the common start of the trajectory benchmarks (bench_xtc.sh,
# bench_xtc_write.sh, bench_netcdf.sh, bench_pbc.sh) and of the ray tracer's
# (bench_rtfloor.sh, bench_table2.sh), sourced after `set -eu` with the
# script's arguments: `. "$(dirname "$0")/lib.sh" "$@"`. Sets src (the source tree), build
# (the build tree: $1, else src), out (bench-out/ in the source tree, made here) and natoms
# (NATOMS, default 1,000,000). `bench_replicate PDB` writes 1tii.pdb replicated to natoms
# atoms (replicate.py) into PDB unless it is already there.
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=$(cd "${1:-$src}" && pwd)
out="$src/bench-out"
mkdir -p "$out"
natoms=${NATOMS:-1000000}

bench_replicate() {
    [ -f "$1" ] || /usr/bin/python3 "$src/scripts/bench/replicate.py" "$src/tests/data/1tii.pdb" "$natoms" "$1"
}
