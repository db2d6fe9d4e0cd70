#!/usr/bin/env bash
# bench_table2.sh: the paper's Table 1 and Table 2 settings on the CPU (issue 21):
# TachyonInternal on nested transparent QuickSurf surfaces (bench_table2.tcl: il2 replicated
# to T2_ATOMS atoms, an Opaque inner and a Transparent outer surface, depth cueing, AO 3
# samples per hit) at T2_SIZE pixels square, for Table 2's rows (1 and 12 samples, shadows
# on/off, AO on/off, ray depth 1, 10 and 20) and Table 1's (48 samples, shadows, AO, depth
# 20), on all threads; then the rows of T2_ONE_ROWS again on 1 thread (MOLSCOPE_THREADS=1,
# another process: CPU time); then Debian's tachyon on the exported scene of each row (its
# Raydepth set to the row's depth), all threads, in the same run, under a memory cap
# (ulimit -v) and `timeout`. tachyon renders each row at 1 sample first; a row of more
# samples is rendered for real when that 1-sample trace times the samples is below
# T2_TACHYON_MAX seconds (and `timeout` stops it there), else, or when it was stopped,
# extrapolated from the 1-sample run (its trace times the samples, plus its preprocessing;
# its CPU beyond the parse in the same proportion) and marked so. A scene whose estimated
# size in tachyon (T2_TACHYON_BPO bytes an object: 550-580 measured at 56k and 500k atoms)
# passes the cap is not run, and the table says so. The rows of T2_FLOOR_ROWS are rendered
# once more with their rays dumped (MOLSCOPE_RT_RAYDUMP), and rt_floor traces those rays with
# Embree alone, its scenes built as the render's (-v placed), on all threads: the floor of
# the row (Embree's build and trace, CPU s). Logs in bench-out/table2/ (T2_OUT).
#
#   scripts/bench/bench_table2.sh [builddir]
#   T2_ATOMS=56000 (2400000: the paper's scale)  T2_SIZE=1024  T2_ROWS="spp sh ao depth ..."
#   T2_ONE_ROWS="0 2 5" (row indices, "": none)  T2_RENDERER=TachyonInternal
#   T2_TACHYON=1 (0: no tachyon)  T2_TACHYON_MEM=7 (GB)  T2_TACHYON_MAX=3600 (s)
#   T2_TACHYON_BPO=600  T2_FLOOR_ROWS="0 2 5" (row indices, "": none; 32 bytes a ray on disc:
#   1.6 GB for a 12-sample row at 1024 x 1024)
set -euo pipefail
. "$(dirname "$0")/lib.sh" "$@"
out=${T2_OUT:-$out/table2}
mkdir -p "$out"
atoms=${T2_ATOMS:-56000}
size=${T2_SIZE:-1024}
renderer=${T2_RENDERER:-TachyonInternal}
tmem=${T2_TACHYON_MEM:-7} tmax=${T2_TACHYON_MAX:-3600} bpo=${T2_TACHYON_BPO:-600}
pdb=$src/bench-out/table2/il2_$atoms.pdb
mkdir -p "$(dirname "$pdb")"
[ -s "$pdb" ] || /usr/bin/python3 "$src/scripts/bench/replicate.py" "$src/tests/data/il2.pdb" "$atoms" "$pdb" >&2
# the rows: spp shadows ao depth (the paper's Table 2, then Table 1)
rows=${T2_ROWS:-"1 0 0 1  1 1 0 20  1 1 1 20  12 1 1 1  12 1 1 10  12 1 1 20  48 1 1 20"}
export MOLSCOPE_TCLLIB=$src/tcl MOLSCOPE_PLUGINDIR=$build/plugins/.libs MOLSCOPE_NOREADLINE=1
tachyon_on=0
[ "${T2_TACHYON:-1}" = 1 ] && [ "$renderer" = TachyonInternal ] && command -v tachyon > /dev/null &&
    tachyon_on=1
echo "== Tables 1 and 2 settings: il2 x $atoms atoms, nested QuickSurf surfaces, ${size}x$size," \
     "$renderer, $(nproc) threads; $(date -u '+%F %H:%M'), load $(cut -d' ' -f1-3 /proc/loadavg)"

run_molscope() {   # log rows [export]: one process rendering the rows
    local export=()
    [ -n "${3:-}" ] && export=(BENCH_EXPORT="$3")
    env BENCH_PDB="$pdb" BENCH_SIZE="$size" BENCH_OUT="$out" BENCH_ROWS="$2" \
        BENCH_RENDERER="$renderer" "${export[@]}" \
        /usr/bin/time -f "peak RSS %M kB" "$build/src/molscope" -dispdev text \
        -e "$src/scripts/bench/bench_table2.tcl" < /dev/null > "$1.raw" 2> "$1.err" ||
        { cat "$1.err" >&2; return 1; }
    awk -F'\t' '$1 == "surfaces" {print "loaded and built the surfaces in " $2 " s" > "/dev/stderr"}
                $1 == "row" {print $2, $3, $4, $5, $6, $7}' "$1.raw" > "$1"
    grep -h "peak RSS" "$1.err" >&2
}
export_prefix=
[ "$tachyon_on" = 1 ] && export_prefix=$out/scene
run_molscope "$out/ti.log" "$rows" "$export_prefix"
one_rows=
i=0
while read -r spp sh ao depth _; do
    for k in ${T2_ONE_ROWS-0 2 5}; do [ "$k" = "$i" ] && one_rows="$one_rows $spp $sh $ao $depth"; done
    i=$((i + 1))
done < "$out/ti.log"
: > "$out/ti1.log"
[ -n "$one_rows" ] && MOLSCOPE_THREADS=1 run_molscope "$out/ti1.log" "$one_rows"

# the floor of the rows of T2_FLOOR_ROWS: "spp sh ao depth cpu" lines (build + trace)
: > "$out/floor.log"
floor_rows=${T2_FLOOR_ROWS-0 2 5}
if [ "$renderer" = TachyonInternal ] && [ -n "$floor_rows" ]; then
    (cd "$build" && make -s scripts/bench/rt_floor)
    trap 'rm -f "$out/floor.rays"' EXIT     # 32 bytes a ray: not left behind by a failure
    i=0
    while read -r spp sh ao depth _; do
        for k in $floor_rows; do
            [ "$k" = "$i" ] || continue
            MOLSCOPE_RT_RAYDUMP=$out/floor.rays run_molscope "$out/dump.log" "$spp $sh $ao $depth" 2> /dev/null
            "$build/scripts/bench/rt_floor" -t "$(nproc)" -v placed "$out/floor.rays" > "$out/floor_$i.log"
            rm -f "$out/floor.rays"
            awk -v r="$spp $sh $ao $depth" '/^floor / {for (f = 1; f <= NF; f++) if ($f ~ /^build_cpu=/) b = substr($f, 11)}
                /^total / {split($4, a, "="); printf "%s %.2f\n", r, b + a[2]}' "$out/floor_$i.log" >> "$out/floor.log"
        done
        i=$((i + 1))
    done < "$out/ti.log"
fi

# tachyon on one scene: file depth aasamples -> "parse preprocess trace cpu rss" (seconds, kB),
# or "fail <status>"
tachyon_run() {
    local log=$out/tachyon.log st=0
    sed -i "1,40s/^\( *\)Raydepth [0-9]*/\1Raydepth $2/" "$1"
    ( ulimit -v $((tmem * 1024 * 1024)); timeout "$tmax" /usr/bin/time -f "cpu %U %S rss %M" \
        tachyon -numthreads "$(nproc)" -aasamples "$3" -fullshade -format TARGA \
        -o "$out/tachyon.tga" "$1" ) > "$log" 2>&1 || st=$?
    [ "$st" = 0 ] || { echo "fail $st"; return 0; }
    tr '\r' '\n' < "$log" | awk '/Scene Parsing Time/ {p = $4} /Preprocessing Time/ {q = $3}
        /Ray Tracing Time/ {t = $4} /^cpu / {c = $2 + $3; m = $5}
        END {printf "%.2f %.2f %.2f %.2f %d\n", p, q, t, c, m}'
}
# Objects in a Tachyon scene file (triangles of its meshes and single primitives).
scene_objects() {
    awk '$1 == "TriMesh" {n += $2} $1 ~ /^(Sphere|FCylinder|Cylinder|Tri|STri|VCSTri|Ring|Cone)$/ {n++}
         END {print n + 0}' "$1"
}
# tachyon's columns for row i: "wall cpu rss note"; wall: preprocess + trace; cpu: the
# process's less its parse (single-threaded)
tachyon_cols() {
    local f=$out/scene_$1.dat spp=$2 depth=$3 objs need p q t c m note=""
    objs=$(scene_objects "$f")
    need=$(awk -v o="$objs" -v b="$bpo" 'BEGIN {printf "%.1f", o * b / 1e9}')
    if awk -v n="$need" -v m="$tmem" 'BEGIN {exit !(n > m)}'; then
        echo "- - - (tachyon: $objs objects, about $need GB at $bpo bytes each, over the $tmem GB cap: not run)"
        return
    fi
    read -r p q t c m < <(tachyon_run "$f" "$depth" 0)
    if [ "$p" = fail ]; then echo "- - - (tachyon failed: status $q, $objs objects, cap $tmem GB)"; return; fi
    if [ "$spp" -gt 1 ]; then
        local real=fail
        if awk -v t="$t" -v s="$spp" -v x="$tmax" 'BEGIN {exit !(t * s < x)}'; then
            real=$(tachyon_run "$f" "$depth" $((spp - 1)))
            note=" (tachyon extrapolated: its $spp-sample run ended with status ${real#fail }, 124: past the ${tmax} s cap)"
        fi
        if [ "${real%% *}" != fail ]; then
            read -r p q t c m <<< "$real"
            note=""
        else
            # its CPU beyond the parse grows as its wall time: preprocessing once, the trace x spp
            c=$(awk -v c="$c" -v p="$p" -v q="$q" -v t="$t" -v s="$spp" \
                'BEGIN {print p + (c - p) * (q + t * s) / (q + t)}')
            t=$(awk -v t="$t" -v s="$spp" 'BEGIN {print t * s}')
            note=${note:-" (tachyon extrapolated: its 1-sample trace x $spp)"}
        fi
    fi
    awk -v p="$p" -v q="$q" -v t="$t" -v c="$c" -v m="$m" -v n="$note" \
        'BEGIN {printf "%.1f %.1f %.2f%s\n", q + t, c - p, m / 1048576, n}'
}

row_col() {   # log column spp sh ao depth -> that column of the row in the log, or -
    awk -v a="$3" -v b="$4" -v c="$5" -v d="$6" -v k="$2" \
        '$1 == a && $2 == b && $3 == c && $4 == d {x = $k} END {print (x == "" ? "-" : x)}' "$1"
}
echo
echo "| samples | shadows | AO | depth | $renderer s (CPU s) | 1 thread CPU s | Embree floor CPU s | tachyon s (CPU s) | tachyon GB | wall ratio | CPU ratio | tachyon / floor CPU |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
i=0
while read -r spp sh ao depth wall cpu; do
    tw=- tc=- tg=- note=""
    if [ "$tachyon_on" = 1 ]; then
        read -r tw tc tg note < <(tachyon_cols "$i" "$spp" "$depth")
        rm -f "$out/scene_$i.dat"
    fi
    wr=$(awk -v a="$wall" -v b="$tw" 'BEGIN {if (b + 0 > 0) printf "%.1fx", b / a; else print "-"}')
    cr=$(awk -v a="$cpu" -v b="$tc" 'BEGIN {if (b + 0 > 0) printf "%.1fx", b / a; else print "-"}')
    fl=$(row_col "$out/floor.log" 5 "$spp" "$sh" "$ao" "$depth")
    fr=$(awk -v a="$fl" -v b="$tc" 'BEGIN {if (a + 0 > 0 && b + 0 > 0) printf "%.1fx", b / a; else print "-"}')
    echo "| $spp | $sh | $ao | $depth | $wall ($cpu) | $(row_col "$out/ti1.log" 6 "$spp" "$sh" "$ao" "$depth") | $fl | $tw ($tc) | $tg | $wr | $cr | $fr |${note:+ $note}"
    i=$((i + 1))
done < "$out/ti.log"
echo "($renderer: the render command, Embree build and PNG included, not the surfaces (built"
echo " before the first row). tachyon: preprocessing + ray tracing; its CPU: the whole run less"
echo " its parse of the scene file; GB: its peak resident memory. Embree floor: the row's rays"
echo " traced by Embree alone (rt_floor -v placed), its build and trace, all threads)"
