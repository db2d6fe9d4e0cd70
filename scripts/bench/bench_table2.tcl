# bench_table2.tcl: molscope's side of bench_table2.sh: the paper's Table 2 settings on the
# CPU. $env(BENCH_PDB) (il2 replicated) drawn as two nested QuickSurf surfaces (the inner one
# Opaque at radius scale 0.8, the outer Transparent at 1.4), depth cueing, AO 3 samples per
# hit, $env(BENCH_SIZE) pixels square. The surfaces are built first (a render of 16 x 16
# pixels, untimed: "surfaces<TAB>wall s" with the load). For each row of $env(BENCH_ROWS) ("spp shadows ao
# depth" ...) the renderer renders once and prints
# "row<TAB>spp<TAB>shadows<TAB>ao<TAB>depth<TAB>wall s<TAB>CPU s"; with BENCH_EXPORT set, the
# scene of each row is also written to $env(BENCH_EXPORT)_<row>.dat by `render Tachyon`.
# BENCH_RENDERER (default TachyonInternal) names the device that renders the rows
# (TachyonLOpenCLInternal: the OpenCL tracer).
source [file join [file dirname [info script]] bench_util.tcl]
set renderer TachyonInternal
if {[info exists env(BENCH_RENDERER)]} { set renderer $env(BENCH_RENDERER) }
set t0 [clock microseconds]
mol new $env(BENCH_PDB) waitfor all
mol modstyle 0 top QuickSurf 0.8 0.5 1.0 1
mol modmaterial 0 top Opaque
mol representation QuickSurf 1.4 0.5 1.0 1
mol material Transparent
mol addrep top
mol repinfo top 1
axes location off
display depthcue on
render aosamples TachyonInternal 3
render aosamples Tachyon 3
display resize 16 16
render aosamples $renderer 3
render aasamples $renderer 0
render $renderer $env(BENCH_OUT)/warm.png
display resize $env(BENCH_SIZE) $env(BENCH_SIZE)
puts [format "surfaces\t%.2f" [expr {([clock microseconds] - $t0) / 1e6}]]
set i 0
foreach {spp shadows ao depth} $env(BENCH_ROWS) {
    display shadows [expr {$shadows ? "on" : "off"}]
    display ambientocclusion [expr {$ao ? "on" : "off"}]
    render aasamples $renderer [expr {$spp - 1}]
    set env(MOLSCOPE_RT_DEPTH) $depth
    set c0 [cputicks]
    set t0 [clock microseconds]
    render $renderer $env(BENCH_OUT)/table2_$i.png
    puts [format "row\t%d\t%d\t%d\t%d\t%.3f\t%.2f" $spp $shadows $ao $depth \
              [expr {([clock microseconds] - $t0) / 1e6}] [expr {([cputicks] - $c0) / 100.0}]]
    if {[info exists env(BENCH_EXPORT)]} { render Tachyon $env(BENCH_EXPORT)_$i.dat }
    incr i
}
