#!/usr/bin/env bash
# bench_live.sh: issue 24's benchmark of the live page (bench_live.py): a drag on a 100k-atom
# NewCartoon at 1024x768 (target 10 images/s), a view change on 1tii (100 ms) and a rep
# parameter typed in the page (300 ms), in headless chromium, with raster-only and
# progressive images; then the same with molscope on one thread (MOLSCOPE_THREADS=1); then
# the drag with its meshes drawn whole (MOLSCOPE_LIVE_LOD=0), as before the level of detail.
#   scripts/bench/bench_live.sh [natoms]
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x src/molscope ] || { echo "bench_live: build molscope first (make)" >&2; exit 1; }
natoms=${1:-100000}
mkdir -p bench-out
pdb=bench-out/live$natoms.pdb
[ -f "$pdb" ] || /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb "$natoms" "$pdb"
export MOLSCOPE=$PWD/src/molscope MOLSCOPE_TCLLIB=$PWD/tcl MOLSCOPE_PLUGINDIR=$PWD/plugins/.libs
export MOLSCOPE_NOREADLINE=1 MS_TEST_OUT=$PWD/bench-out
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "## all threads"
/usr/bin/python3 scripts/bench/bench_live.py "$pdb" tests/data/1tii.pdb
echo "## one thread (MOLSCOPE_THREADS=1)"
MOLSCOPE_THREADS=1 /usr/bin/python3 scripts/bench/bench_live.py "$pdb" tests/data/1tii.pdb
echo "## the drag without the level of detail (MOLSCOPE_LIVE_LOD=0), all threads, then one"
MOLSCOPE_LIVE_LOD=0 /usr/bin/python3 scripts/bench/bench_live.py "$pdb" tests/data/1tii.pdb --drag
MOLSCOPE_LIVE_LOD=0 MOLSCOPE_THREADS=1 /usr/bin/python3 scripts/bench/bench_live.py "$pdb" tests/data/1tii.pdb --drag
