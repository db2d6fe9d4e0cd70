# bench_imd.tcl: frames per second molscope receives over IMD from the fake simulation
# (tests/python/imdserver.py --same) for a molecule of natoms atoms: `imd keep keep`, frames
# frames, timed from `imd connect` to the last frame applied. Prints
# "imd <keep> <frames> <seconds> <cpu-seconds>" (CPU of this process, from /proc/self/stat).
lassign $argv server natoms frames keep
proc cpu {} {
    set f [open /proc/self/stat]
    set fields [split [lindex [split [read $f] )] 1]]
    close $f
    expr {([lindex $fields 12] + [lindex $fields 13]) / 100.0}
}
# the last frame is applied when the last frame's temperature (300 + k) is there
proc poll {} {
    if {[molinfo top get temperature frame last] >= 300 + $::frames} { set ::done 1 } else { after 2 poll }
}
set srv [open "|/usr/bin/python3 $server --natoms $natoms --frames $frames --same 2>@stderr" r]
gets $srv port
mol new atoms $natoms
animate dup top
imd keep $keep
set c0 [cpu]
set t0 [clock microseconds]
imd connect 127.0.0.1 $port
poll
vwait ::done
set t [expr {([clock microseconds] - $t0) / 1e6}]
set c [expr {[cpu] - $c0}]
imd detach
read $srv
close $srv
puts "imd $keep $frames $t $c [molinfo top get numframes]"
quit
