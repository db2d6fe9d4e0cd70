# bench_reps.tcl: molscope's side of the representation benchmark. Loads $env(BENCH_PDB)
# (1tii replicated to ~1M atoms: replicate.py drops the HELIX/SHEET records, so the
# secondary structure of 1tii is copied onto every copy with `$sel set structure`), then for
# VDW, Licorice and NewCartoon (or the methods and colourings $env(BENCH_METHODS) lists, as
# "Bonds Element CPK Element ...") times, $env(BENCH_REPEAT) times each:
#   first    a new rep's first build (`mol addrep`, then `mol repinfo`, which brings the rep
#            up to date as the scene does): selection, colours and geometry into new memory;
#   rebuild  the same rep after a frame change (frame 1 is a copy of frame 0): the geometry
#            again, into the memory of the last build.
# Prints "method<TAB>primitives<TAB>first median s<TAB>first best s<TAB>rebuild median s<TAB>
# rebuild best s<TAB>first CPU s<TAB>rebuild CPU s": wall times, and the process's CPU time
# (all threads, from /proc/self/stat, 10 ms ticks) per build, which varies less on a busy
# machine.
proc median {l} {
    set l [lsort -real $l]
    set n [llength $l]
    expr {$n % 2 ? [lindex $l [expr {$n / 2}]] : ([lindex $l [expr {$n / 2 - 1}]] + [lindex $l [expr {$n / 2}]]) / 2.0}
}
source [file join [file dirname [info script]] bench_util.tcl]
# Wall seconds of a script; the CPU ticks it took are added to ::cpu.
proc seconds {script} {
    set c0 [cputicks]
    set t0 [clock microseconds]
    uplevel 1 $script
    set t [expr {([clock microseconds] - $t0) / 1e6}]
    set ::cpu [expr {$::cpu + [cputicks] - $c0}]
    return $t
}
set ::cpu 0
set ref [mol new $env(BENCH_SRC) waitfor all]
set ss [[atomselect $ref all] get structure]
set nref [molinfo $ref get numatoms]
mol delete $ref

set t [seconds {set m [mol new $env(BENCH_PDB) waitfor all]}]
set n [molinfo $m get numatoms]
puts [format "load\t%d atoms\t%.2f" $n $t]
set all {}
for {set k 0} {$k < $n / $nref} {incr k} { lappend all {*}$ss }
[atomselect $m all] set structure $all
animate dup frame 0 $m
mol delrep 0 $m

set methods {VDW Element Licorice Element NewCartoon Structure}
if {[info exists env(BENCH_METHODS)]} { set methods $env(BENCH_METHODS) }
foreach {style color} $methods {
    set first {}
    set again {}
    mol representation $style
    mol color $color
    set cfirst 0
    set cagain 0
    for {set r 0} {$r < $env(BENCH_REPEAT)} {incr r} {
        animate goto 0
        mol addrep $m
        set ::cpu 0
        lappend first [seconds {mol repinfo $m 0}]
        set cfirst [expr {$cfirst + $::cpu}]
        set ::cpu 0
        for {set k 1} {$k <= 2} {incr k} {
            animate goto [expr {$k % 2}]
            lappend again [seconds {mol repinfo $m 0}]
        }
        set cagain [expr {$cagain + $::cpu}]
        set info [mol repinfo $m 0]
        mol delrep 0 $m
    }
    set prims [expr {[dict get $info spheres] + [dict get $info cylinders] + [dict get $info triangles]}]
    set hz 100.0
    puts [format "%s\t%d\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f" $style $prims [median $first] \
              [tcl::mathfunc::min {*}$first] [median $again] [tcl::mathfunc::min {*}$again] \
              [expr {$cfirst / $hz / [llength $first]}] [expr {$cagain / $hz / [llength $again]}]]
}
quit
