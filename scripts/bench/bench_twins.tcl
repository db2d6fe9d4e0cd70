# bench_twins.tcl: molscope's side of bench_twins.sh, the neighbour-search and OpenCL
# benchmark of issue 17. Loads $env(BENCH_PDB) (1tii replicated), then times, best of
# $env(BENCH_REPEAT) (wall seconds, and the process's CPU seconds of that best run, all
# threads, from /proc/self/stat):
#   bonds       `mol bondsrecalc`: the distance bond search
#   dynbonds    a DynamicBonds rep's first build (cutoff 1.6)
#   hbonds      an HBonds rep's first build (cutoff 3.0, angle 20)
#   within      `within 4 of` half the system, `same residue as within 3 of` some CA atoms
#   contacts    `measure contacts 3.0` within half the system (bonded pairs left out)
#   dssp        `mol ssrecalc`: DSSP, its hydrogen bonds through the CA grid
#   quicksurf   a QuickSurf rep's first build (resolution 1.0, grid spacing 1.0)
#   oclrender   `render TachyonLOpenCLInternal` of 1tii in VDW at 512x512 (the engine
#               started by an untimed first render)
# Each line: "name<TAB>wall s<TAB>CPU s<TAB>digest", the digest a CRC of what the step
# computed (bonds, pair lists, selections, structure, picture; "-" for QuickSurf), so that
# two builds can be checked to give the same results.
source [file join [file dirname [info script]] bench_util.tcl]
# Best wall time of running script R times, with that run's CPU time; sets ::result.
proc best {name script digest} {
    set bw 1e9
    set bc 0
    for {set r 0} {$r < $::env(BENCH_REPEAT)} {incr r} {
        set c0 [cputicks]
        set t0 [clock microseconds]
        uplevel #0 $script
        set t [expr {([clock microseconds] - $t0) / 1e6}]
        set c [expr {([cputicks] - $c0) / 100.0}]
        if {$t < $bw} { set bw $t; set bc $c }
    }
    puts [format "%s\t%.3f\t%.2f\t%s" $name $bw $bc [uplevel #0 $digest]]
}
proc crc {s} { format %08x [zlib crc32 $s] }
proc repbuild {m style} {
    mol representation {*}$style
    mol selection all
    mol addrep $m
    mol repinfo $m 0
}
proc repdigest {m} {
    set f $::env(BENCH_OUT)/twins.dat
    render Tachyon $f
    set fd [open $f]
    set s [read $fd]
    close $fd
    mol delrep 0 $m
    crc $s
}

set m [mol new $env(BENCH_PDB) waitfor all]
mol delrep 0 $m
display resize 64 64
set all [atomselect $m all]
set n [$all num]
puts [format "load\t%d atoms" $n]
set half [expr {$n / 2}]
best bonds {mol bondsrecalc $m} {crc [$all getbonds]}
best dynbonds {repbuild $m {DynamicBonds 1.6 0.3 6}; mol delrep 0 $m} \
    {repbuild $m {DynamicBonds 1.6 0.3 6}; repdigest $m}
best hbonds {repbuild $m {HBonds 3.0 20 1}; mol delrep 0 $m} \
    {repbuild $m {HBonds 3.0 20 1}; repdigest $m}
set s1 [atomselect $m "index < $half"]
best within {
    set ::w1 [[atomselect $m "within 4 of (index < $half)"] list]
    set ::w2 [[atomselect $m "same residue as within 3 of (name CA and x < 40)"] list]
} {crc [list $::w1 $::w2]}
best contacts {set ::c [measure contacts 3.0 $s1]} {crc $::c}
best dssp {mol ssrecalc $m} {crc [$all get structure]}
best quicksurf {repbuild $m {QuickSurf 1.0 0.5 1.0 1.0}; mol delrep 0 $m} {expr {"-"}}

mol delete $m
set m [mol new $env(BENCH_SRC) waitfor all]
mol modstyle 0 $m VDW 1.0 12
display resize 512 512
set f $env(BENCH_OUT)/twins.ppm
render TachyonLOpenCLInternal $f
best oclrender {render TachyonLOpenCLInternal $f} {
    set fd [open $f rb]; set s [read $fd]; close $fd; crc $s
}
quit
