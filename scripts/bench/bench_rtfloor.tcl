# bench_rtfloor.tcl: molscope's side of bench_rtfloor.sh: the "ambient occlusion on spheres"
# scene of issue 21 ($env(BENCH_PDB): il2 replicated 27 times, VDW, AOChalky, shadows and
# ambient occlusion, 800 x 800, aasamples 4, aosamples 12), rendered by TachyonInternal
# $env(BENCH_REPEAT) times to $env(BENCH_IMAGE) (BENCH_RENDERER=TachyonLOpenCLInternal: the
# OpenCL tracer instead); each render prints
# "render<TAB>wall s<TAB>CPU s" (CPU: the process's, all threads, /proc/self/stat).
# With BENCH_EXPORT set, the scene is also written there by `render Tachyon`. BENCH_STYLE
# draws another representation instead of VDW (e.g. "Licorice 0.3 12 12").
source [file join [file dirname [info script]] bench_util.tcl]
mol new $env(BENCH_PDB) waitfor all
set style VDW
if {[info exists env(BENCH_STYLE)]} { set style $env(BENCH_STYLE) }
mol modstyle 0 top {*}$style
mol modmaterial 0 top AOChalky
display resize 800 800
axes location off
scale by 1.5
display shadows on
display ambientocclusion on
set renderer TachyonInternal
if {[info exists env(BENCH_RENDERER)]} { set renderer $env(BENCH_RENDERER) }
render aasamples $renderer 4
render aosamples $renderer 12
for {set r 0} {$r < $env(BENCH_REPEAT)} {incr r} {
    set c0 [cputicks]
    set t0 [clock microseconds]
    render $renderer $env(BENCH_IMAGE)
    puts [format "render\t%.3f\t%.2f" [expr {([clock microseconds] - $t0) / 1e6}] \
              [expr {([cputicks] - $c0) / 100.0}]]
}
if {[info exists env(BENCH_EXPORT)]} { render Tachyon $env(BENCH_EXPORT) }
