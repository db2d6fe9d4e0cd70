#!/usr/bin/env bash
# bench_ocl.sh: issue 8's benchmark. TachyonLOpenCLInternal against TachyonInternal on
# TachyonInternal's benchmark scene (bench_rt.c: 1tii replicated to a million atoms, VDW and
# Licorice with a transparent surface, 1024 x 1024, shadows, AO with 12 samples), in the same
# run: for each sample count TachyonInternal renders, then the OpenCL tracer on the device
# MOLSCOPE_OPENCL_DEVICE names (else the first GPU, else PoCL on the CPU). Prints a row per
# sample count: wall times (build + trace), their ratio, rays per second of each, and the
# mean difference of the two images.
#
#   scripts/bench/bench_ocl.sh [size] [spp...]        (defaults: 1024, and 1 12)
# On PoCL 144 samples take about 12 times the 12-sample row; on a GPU add 144:
#   MOLSCOPE_OPENCL_DEVICE=NVIDIA scripts/bench/bench_ocl.sh 1024 1 12 144
set -euo pipefail
cd "$(dirname "$0")/../.."
SIZE=${1:-1024}
shift || true
SPPS=${*:-1 12}
out=bench-out
mkdir -p $out
: > $out/ocl.log
make -s scripts/bench/bench_rt
PY=/usr/bin/python3

echo "== TachyonLOpenCLInternal and TachyonInternal, ${SIZE}x${SIZE}, $(date -u +%F)"
BENCH_RT_NOEXPORT=1 BENCH_RT_TRACERS="rt ocl" ./scripts/bench/bench_rt tests/data 176 "$SIZE" $out $SPPS |
    tee $out/ocl.log
device=$(grep '^ocl device: ' $out/ocl.log | tail -1 | cut -d' ' -f3-)
get() { printf '%s\n' "$1" | tr ' ' '\n' | awk -F= -v k="$2" '$1 == k {print $2}'; }
echo
echo "OpenCL device: ${device:-none (fell back)}"
echo "| spp | TachyonInternal s (build + trace) | OpenCL s (build + trace) | OpenCL / TI | TI Mrays/s | OpenCL Mrays/s | rays | mean abs diff |"
echo "|---|---|---|---|---|---|---|---|"
for spp in $SPPS; do
    rt=$(grep "^rt spp=$spp " $out/ocl.log | tail -1 || true)
    cl=$(grep "^ocl spp=$spp " $out/ocl.log | tail -1 || true)
    [ -n "$rt" ] && [ -n "$cl" ] || { echo "| $spp | (no result) |"; continue; }
    diff=$($PY - $out/rt_$spp.png $out/ocl_$spp.png <<'PY' 2>/dev/null || echo -
import sys
import numpy as np
from PIL import Image
a, b = (np.asarray(Image.open(f).convert("RGB"), dtype=float) for f in sys.argv[1:3])
print("%.3f" % np.abs(a - b).mean())
PY
)
    printf '| %4s | %.2f (%.2f + %.2f) | %.2f (%.2f + %.2f) | %.1fx | %s | %s | %.1f M | %s |\n' "$spp" \
        "$(get "$rt" total)" "$(get "$rt" build)" "$(get "$rt" trace)" \
        "$(get "$cl" total)" "$(get "$cl" build)" "$(get "$cl" trace)" \
        "$(awk -v a="$(get "$cl" total)" -v b="$(get "$rt" total)" 'BEGIN{print a / b}')" \
        "$(get "$rt" mrays)" "$(get "$cl" mrays)" \
        "$(awk -v r="$(get "$cl" rays)" 'BEGIN{print r / 1e6}')" "$diff"
done
