#!/usr/bin/env bash
# bench_rtfloor.sh: issue 21's benchmark: TachyonInternal at Embree's limit on ambient
# occlusion. The scene (bench_rtfloor.tcl): il2 replicated 27 times (56,268 atoms) as VDW,
# AOChalky, shadows and ambient occlusion, 800 x 800, aasamples 4 (5 samples a pixel),
# aosamples 12. In one run, on 1 thread and on all threads:
#   - TachyonInternal renders it RTFLOOR_RUNS times (wall and CPU seconds: best and median);
#   - its rays, dumped once by MOLSCOPE_RT_RAYDUMP, are traced by Embree alone
#     (rt_floor.c) for each variant of RTFLOOR_VARIANTS: Mrays/s per ray kind and the
#     floor of the render (best of RTFLOOR_RUNS);
#   - Debian's tachyon renders the scene `render Tachyon` exported, at the same samples
#     (-aasamples 4 -fullshade), RTFLOOR_RUNS times.
# Prints a table for doc/BENCHMARKS.md; logs in bench-out/rtfloor/.
#
#   scripts/bench/bench_rtfloor.sh [builddir]
#   RTFLOOR_RUNS=3  RTFLOOR_VARIANTS="builtin instance user packet cache own"  RTFLOOR_THREADS="1 N"
#   (own where the CPU has AVX2; rt_floor also has camera8: the camera rays as coherent
#   packets of 8, nbr, and -ab: a variant beside builtin in one process, chunk by chunk)
#   RTFLOOR_BEFORE=path/to/molscope: also time that binary (an older build) in the same run,
#   and compare its picture with this build's pixel by pixel
set -euo pipefail
. "$(dirname "$0")/lib.sh" "$@"
out=$out/rtfloor
mkdir -p "$out"
runs=${RTFLOOR_RUNS:-3}
# own (a tree of our own) wants AVX2 and FMA
own=$(grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo && echo own || true)
variants=${RTFLOOR_VARIANTS:-builtin instance user packet cache $own}
before=${RTFLOOR_BEFORE:-}
threads=${RTFLOOR_THREADS:-1 $(nproc)}
floor=$build/scripts/bench/rt_floor
(cd "$build" && make -s scripts/bench/rt_floor)
pdb=$out/ao27.pdb
[ -s "$pdb" ] || /usr/bin/python3 "$src/scripts/bench/replicate.py" "$src/tests/data/il2.pdb" 56000 "$pdb"
export MOLSCOPE_TCLLIB=$src/tcl MOLSCOPE_PLUGINDIR=$build/plugins/.libs MOLSCOPE_NOREADLINE=1

molscope() {   # binary, threads, repeats, [extra environment...]: the render lines
    local bin=$1 t=$2 r=$3
    shift 3
    env MOLSCOPE_THREADS="$t" BENCH_PDB="$pdb" BENCH_REPEAT="$r" BENCH_IMAGE="$out/ti.png" "$@" \
        "$bin" -dispdev text -e "$src/scripts/bench/bench_rtfloor.tcl" < /dev/null |
        awk -F'\t' '$1 == "render" {print $2, $3}'
}
# "best median" of a column of numbers
stats() { sort -g | awk '{v[NR] = $1} END {printf "%.2f %.2f\n", v[1], NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
tachyon_run() {   # threads: "trace_wall cpu"
    /usr/bin/time -f "cpu %U %S" tachyon -numthreads "$1" -aasamples 4 -fullshade -format TARGA \
        -o "$out/tachyon.tga" "$out/scene.dat" 2>&1 | tr '\r' '\n' |
        awk '/Preprocessing Time/ {q = $3} /Ray Tracing Time/ {t = $4} /^cpu / {c = $2 + $3}
             END {printf "%.3f %.2f\n", q + t, c}'
}

echo "== AO on spheres: TachyonInternal, Embree-only floor, tachyon; $(date -u '+%F %H:%M'), load $(cut -d' ' -f1-3 /proc/loadavg)"
# the dump and the export (all threads, one render)
molscope "$build/src/molscope" "$(nproc)" 1 MOLSCOPE_RT_RAYDUMP="$out/ao.rays" BENCH_EXPORT="$out/scene.dat" > /dev/null
cp "$out/ti.png" "$out/ti_ref.png"
rm -f "$out/ti_before.png"
if [ -n "$before" ]; then
    molscope "$before" "$(nproc)" 1 > /dev/null
    cp "$out/ti.png" "$out/ti_before.png"
fi
rows=()
for t in $threads; do
    molscope "$build/src/molscope" "$t" "$runs" > "$out/ti_$t.log"
    read -r ti_w ti_wm < <(awk '{print $1}' "$out/ti_$t.log" | stats)
    read -r ti_c ti_cm < <(awk '{print $2}' "$out/ti_$t.log" | stats)
    if [ -n "$before" ]; then
        molscope "$before" "$t" "$runs" > "$out/before_$t.log"
        read -r bw bwm < <(awk '{print $1}' "$out/before_$t.log" | stats)
        read -r bc bcm < <(awk '{print $2}' "$out/before_$t.log" | stats)
        echo "    [before, $t threads] TachyonInternal best / median $bw / $bwm s (CPU $bc / $bcm); this build $ti_w / $ti_wm s (CPU $ti_c / $ti_cm)"
    fi
    for v in $variants; do
        "$floor" -t "$t" -v "$v" -r "$runs" "$out/ao.rays" > "$out/floor_${v}_$t.log"
        sed "s/^/    [$v, $t threads] /" "$out/floor_${v}_$t.log"
        eval "fw_$v=$(awk '/^total/ {split($3, a, "="); print a[2]}' "$out/floor_${v}_$t.log")"
        eval "fc_$v=$(awk '/^total/ {split($4, a, "="); print a[2]}' "$out/floor_${v}_$t.log")"
    done
    : > "$out/tachyon_$t.log"
    if command -v tachyon > /dev/null; then
        for ((r = 0; r < runs; r++)); do tachyon_run "$t" >> "$out/tachyon_$t.log"; done
    fi
    read -r ta_w ta_wm < <(awk '{print $1}' "$out/tachyon_$t.log" | stats)
    read -r ta_c ta_cm < <(awk '{print $2}' "$out/tachyon_$t.log" | stats)
    fl="" ; for v in $variants; do eval "fl+=\" \$fw_$v (\$fc_$v)\""; done
    rows+=("$(awk -v t="$t" -v w="$ti_w" -v wm="$ti_wm" -v c="$ti_c" -v cm="$ti_cm" -v fw="$fw_builtin" \
        -v fc="$fc_builtin" -v aw="$ta_w" -v ac="$ta_c" -v fl="$fl" 'BEGIN {
        printf "| %s | %.2f / %.2f (%.2f / %.2f) |%s | %.2fx (%.2fx) | %.2f (%.2f) | %.2fx (%.2fx) |",
            t, w, wm, c, cm, fl, w / fw, c / fc, aw, ac, aw / w, ac / c }')")
done
echo
echo "| threads | TachyonInternal s, best / median (CPU) | floor s: $variants (CPU) | TI / floor (builtin) | tachyon s, best (CPU) | tachyon / TI |"
echo "|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
echo "(TachyonInternal: the whole render command, build and PNG included; floor: Embree alone on the"
echo " dumped rays, best of $runs per kind, summed; tachyon: preprocessing + ray tracing, CPU of the"
echo " whole run including its parse; ratios of best wall times, CPU in brackets)"
/usr/bin/python3 - "$out/ti_ref.png" "$out/tachyon.tga" "$out/ti_before.png" <<'PY' 2>/dev/null || true
import os
import sys
import numpy as np
from PIL import Image
img = [np.asarray(Image.open(f).convert("RGB"), dtype=float) if os.path.exists(f) else None for f in sys.argv[1:4]]
if img[1] is not None:
    print("mean |TachyonInternal - tachyon| of 8-bit channels: %.2f" % np.abs(img[0] - img[1]).mean())
if img[2] is not None:
    d = np.abs(img[0] - img[2])
    print("against the build before: %d of %d pixels differ, by at most %d, mean %.4f of 255"
          % ((d.max(axis=2) > 0).sum(), d.shape[0] * d.shape[1], d.max(), d.mean()))
PY
