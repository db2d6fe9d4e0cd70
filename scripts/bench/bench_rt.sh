#!/usr/bin/env bash
# bench_rt.sh: issue 7's benchmark. TachyonInternal against Debian's tachyon on the same
# scene at equal samples, in the same run: 1tii replicated to a million atoms drawn VDW and
# Licorice with a transparent surface (bench_rt.c), 1024 x 1024, shadows, ambient occlusion
# with 12 samples. The scene is exported once with `render Tachyon`'s device; tachyon renders
# that file with -aasamples N-1 (its N-1 jittered samples plus the pixel centre make N, as
# TachyonInternal's passes do). Each sample count runs TachyonInternal then tachyon, one after
# the other, so both see the same machine load; wall clock and CPU times are printed, with
# the rays per second and the mean difference between the two images.
#
#   scripts/bench/bench_rt.sh [size] [spp...]        (defaults: 1024, and 1 12 144)
#   TACHYON_SPP="1 12"  the sample counts tachyon renders (default "1 12"; at 144 its time is
#                       the 12-sample trace scaled by 12, and says so)
set -euo pipefail
cd "$(dirname "$0")/../.."
SIZE=${1:-1024}
shift || true
SPPS=${*:-1 12 144}
TSPP=${TACHYON_SPP:-1 12}
THREADS=${MOLSCOPE_THREADS:-$(nproc)}
out=bench-out
mkdir -p $out
: > $out/rt.log
make -s scripts/bench/bench_rt
have_tachyon=0
command -v tachyon >/dev/null && have_tachyon=1
PY=/usr/bin/python3

# tachyon's times: "parse preprocess trace cpu" (cpu: user + sys of the whole run)
tachyon_run() {
    local spp=$1 res=$2 img=$3
    local log=$out/tachyon_${spp}_$res.log
    /usr/bin/time -f "cpu %U %S" tachyon -numthreads "$THREADS" -aasamples $((spp > 0 ? spp - 1 : 0)) -res $res $res \
        -fullshade -format TARGA -o "$img" $out/rt_scene.dat > "$log" 2>&1 || true
    tr '\r' '\n' < "$log" | awk '
        /Scene Parsing Time/ {p = $4} /Preprocessing Time/ {q = $3} /Ray Tracing Time/ {t = $4}
        /^cpu / {c = $2 + $3} END {printf "%s %s %s %s\n", p, q, t, c}'
}

echo "== TachyonInternal and tachyon, ${SIZE}x${SIZE}, $THREADS threads, $(date -u +%F)"
first=1
rows=()
base_cpu=""
for spp in $SPPS; do
    export BENCH_RT_NOEXPORT=$((1 - first))
    [ $first = 1 ] && unset BENCH_RT_NOEXPORT
    ./scripts/bench/bench_rt tests/data 176 "$SIZE" $out "$spp" | tee -a $out/rt.log
    line=$(grep "^rt spp=$spp " $out/rt.log | tail -1)
    first=0
    get() { printf '%s\n' "$line" | tr ' ' '\n' | awk -F= -v k="$1" '$1 == k {print $2}'; }
    rt_total=$(get total); rt_build=$(get build); rt_trace=$(get trace); rt_mrays=$(get mrays)
    rt_cpu=$(awk -v a="$(get build_cpu)" -v b="$(get trace_cpu)" 'BEGIN{printf "%.2f", a + b}')
    t_render=-; t_parse=-; t_cpu=-; note=""; diff=-
    if [ $have_tachyon = 1 ]; then
        if [ -z "$base_cpu" ]; then   # parsing and preprocessing alone, to split tachyon's CPU time
            read -r bp bq bt bc < <(tachyon_run 0 8 $out/tachyon_res8.tga)   # (-res 1 1 misbehaves)
            base_cpu=$bc
        fi
        if [[ " $TSPP " == *" $spp "* ]]; then
            read -r tp tq tt tc < <(tachyon_run "$spp" "$SIZE" $out/tachyon_$spp.tga)
            eval "tq_$spp=$tq tt_$spp=$tt tc_$spp=$tc"
            t_render=$(awk -v q="$tq" -v t="$tt" 'BEGIN{printf "%.2f", q + t}')
            parse=$tp
            t_cpu=$(awk -v c="$tc" -v b="$base_cpu" -v q="$bq" 'BEGIN{printf "%.2f", c - b + q}')
            diff=$($PY - $out/rt_$spp.png $out/tachyon_$spp.tga <<'PY' 2>/dev/null || echo -
import sys
import numpy as np
from PIL import Image
a, b = (np.asarray(Image.open(f).convert("RGB"), dtype=float) for f in sys.argv[1:3])
print("%.2f" % np.abs(a - b).mean())
PY
)
        elif [ -n "${tt_12:-}" ]; then
            t_render=$(awk -v q="$tq_12" -v t="$tt_12" -v s="$spp" 'BEGIN{printf "%.1f", q + t * s / 12}')
            t_cpu=$(awk -v c="$tc_12" -v b="$base_cpu" -v q="$bq" -v s="$spp" 'BEGIN{printf "%.1f", q + (c - b) * s / 12}')
            note=" (tachyon extrapolated from 12)"
        fi
    fi
    ratio=$(awk -v a="$rt_total" -v b="$t_render" 'BEGIN{if (b + 0 > 0) printf "%.1fx", b / a; else print "-"}')
    cratio=$(awk -v a="$rt_cpu" -v b="$t_cpu" 'BEGIN{if (b + 0 > 0) printf "%.1fx", b / a; else print "-"}')
    rows+=("$(printf '| %4s | %6.2f (%.2f + %.2f) | %8s | %6s | %6s | %7s | %8s | %6s | %5s |%s' "$spp" \
        "$rt_total" "$rt_build" "$rt_trace" "$t_render" "$ratio" "$rt_cpu" "$t_cpu" "$cratio" \
        "$rt_mrays" "$diff" "$note")")
done
echo
echo "| spp | TachyonInternal s (build + trace) | tachyon s | ratio | TI CPU s | tachyon CPU s | CPU ratio | TI Mrays/s | mean abs diff |"
echo "|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
echo "(tachyon s: preprocessing + ray tracing, not its ${parse:-?} s of parsing the scene file;"
echo " CPU s: all threads; tachyon's: its run less a run at 8x8 pixels (parsing, preprocessing),"
echo " plus its preprocessing wall time; diff: mean |difference| of 8-bit channels)"
