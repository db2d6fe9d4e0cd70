#!/usr/bin/env bash
# bench_table2.sh: the paper's Table 2 settings on the CPU (issue 21): TachyonInternal on
# nested transparent QuickSurf surfaces (bench_table2.tcl: il2 replicated to T2_ATOMS atoms,
# an Opaque inner and a Transparent outer surface, depth cueing, AO 3 samples per hit) at
# T2_SIZE pixels square, for Table 2's rows: 1 and 12 samples, shadows on/off, AO on/off,
# ray depth 1, 10 and 20; then Debian's tachyon on the exported scene of each 1-sample row
# (its Raydepth set to the row's depth), all threads, in the same run. tachyon's 12-sample
# rows are extrapolated from its 1-sample row of the same shadows and AO (12 times its trace),
# and say so. Logs in bench-out/table2/.
#
#   scripts/bench/bench_table2.sh [builddir]
#   T2_ATOMS=56000  T2_SIZE=1024  T2_TACHYON=1 (0: TachyonInternal only)
set -euo pipefail
. "$(dirname "$0")/lib.sh" "$@"
out=$out/table2
mkdir -p "$out"
atoms=${T2_ATOMS:-56000}
size=${T2_SIZE:-1024}
pdb=$out/il2_$atoms.pdb
[ -s "$pdb" ] || /usr/bin/python3 "$src/scripts/bench/replicate.py" "$src/tests/data/il2.pdb" "$atoms" "$pdb" >&2
# the rows: spp shadows ao depth (the paper's Table 2)
rows="1 0 0 1  1 1 0 20  1 1 1 20  12 1 1 1  12 1 1 10  12 1 1 20"
export MOLSCOPE_TCLLIB=$src/tcl MOLSCOPE_PLUGINDIR=$build/plugins/.libs MOLSCOPE_NOREADLINE=1
echo "== Table 2 settings: il2 x $atoms atoms, nested QuickSurf surfaces, ${size}x$size," \
     "$(nproc) threads; $(date -u '+%F %H:%M'), load $(cut -d' ' -f1-3 /proc/loadavg)"
env BENCH_PDB="$pdb" BENCH_SIZE="$size" BENCH_OUT="$out" BENCH_EXPORT="$out/scene" BENCH_ROWS="$rows" \
    "$build/src/molscope" -dispdev text -e "$src/scripts/bench/bench_table2.tcl" < /dev/null |
    awk -F'\t' '$1 == "surfaces" {print "loaded and built the surfaces in " $2 " s" > "/dev/stderr"}
                 $1 == "row" {print $2, $3, $4, $5, $6, $7}' > "$out/ti.log"

tachyon_row() {   # file depth: "preprocess+trace wall, CPU of the run"
    sed -i "s/^\( *\)Raydepth [0-9]*/\1Raydepth $2/" "$1"
    /usr/bin/time -f "cpu %U %S" tachyon -numthreads "$(nproc)" -aasamples 0 -fullshade -format TARGA \
        -o "$out/tachyon.tga" "$1" 2>&1 | tr '\r' '\n' |
        awk '/Preprocessing Time/ {q = $3} /Ray Tracing Time/ {t = $4} /^cpu / {c = $2 + $3}
             END {printf "%.2f %.2f\n", q + t, c}'
}
echo
echo "| samples | shadows | AO | depth | TachyonInternal s (CPU) | tachyon s (CPU) | tachyon / TI |"
echo "|---|---|---|---|---|---|---|"
i=0
while read -r spp sh ao depth wall cpu; do
    tw=- tc=- note=""
    if [ "${T2_TACHYON:-1}" = 1 ] && command -v tachyon > /dev/null; then
        if [ "$spp" = 1 ]; then
            read -r tw tc < <(tachyon_row "$out/scene_$i.dat" "$depth")
            eval "t1_${sh}_$ao=\"$tw $tc\""
        elif [ -n "$(eval echo "\${t1_${sh}_$ao:-}")" ]; then
            read -r w1 c1 < <(eval echo "\$t1_${sh}_$ao")
            tw=$(awk -v w="$w1" -v s="$spp" 'BEGIN {printf "%.1f", w * s}')
            tc=$(awk -v c="$c1" -v s="$spp" 'BEGIN {printf "%.1f", c * s}')
            note=" (tachyon: its 1-sample row x $spp)"
        fi
    fi
    ratio=$(awk -v a="$wall" -v b="$tw" 'BEGIN {if (b + 0 > 0) printf "%.1fx", b / a; else print "-"}')
    echo "| $spp | $sh | $ao | $depth | $wall ($cpu) | $tw ($tc) | $ratio |$note"
    i=$((i + 1))
done < "$out/ti.log"
echo "(TachyonInternal: the render command, Embree build and PNG included, not the surfaces (built"
echo " before the first row). tachyon: preprocessing + ray tracing at -aasamples 0, not its parse of"
echo " the scene file; CPU: the whole run, parse included)"
