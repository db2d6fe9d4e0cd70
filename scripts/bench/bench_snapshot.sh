#!/usr/bin/env bash
# bench_snapshot.sh: issue 5's benchmark: `render snapshot` of 1M-atom VDW and Licorice
# scenes (1tii replicated) at 1024x1024 on every OpenGL back-end that starts, each phase
# timed (upload, draw, readback, PNG), with the occlusion culling on (the default) and off
# (the plain impostor loop, the peer this machine's numbers are quoted against).
#   scripts/bench/bench_snapshot.sh [copies] [size] [frames]
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-176}; S=${2:-1024}; F=${3:-3}
make -s scripts/bench/bench_snapshot
mkdir -p bench-out
echo "## culling on (default)"
scripts/bench/bench_snapshot tests/data "$N" "$S" "$F" all
echo "## culling off: every impostor drawn (MOLSCOPE_GL_CULL=0)"
MOLSCOPE_GL_CULL=0 scripts/bench/bench_snapshot tests/data "$N" "$S" "$F" all
