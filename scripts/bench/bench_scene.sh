#!/usr/bin/env bash
# bench_scene.sh: filling display lists for 1M-atom scenes (VDW, Licorice, a NewCartoon-sized
# mesh) through the display-list API: scripts/bench/bench_scene.c.
set -euo pipefail
cd "$(dirname "$0")/../.."
make -s scripts/bench/bench_scene
scripts/bench/bench_scene tests/data
