#!/usr/bin/env bash
# bench_select.sh: the atom selection benchmark (molscope beside MDAnalysis, 1M and 2M atoms
# by default). Run from a built tree: scripts/bench/bench_select.sh [--repeat R] [N ...]
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x src/molscope ] || { echo "bench_select: build molscope first (make)" >&2; exit 1; }
exec /usr/bin/python3 scripts/bench/bench_select.py "$@"
