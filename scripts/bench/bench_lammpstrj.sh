#!/usr/bin/env bash
# bench_lammpstrj.sh: reading a 1M-atom, 20-frame LAMMPS dump, molscope beside MDAnalysis in
# the same run, wall and one-thread CPU time: see bench_lammpstrj.py, which does the work.
#
# usage: scripts/bench/bench_lammpstrj.sh [builddir]   (NATOMS, NFRAMES, REPEAT override)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
exec /usr/bin/python3 "$here/bench_lammpstrj.py" "$(cd "$here/../.." && pwd)" \
    "$(cd "${1:-$here/../..}" && pwd)"
