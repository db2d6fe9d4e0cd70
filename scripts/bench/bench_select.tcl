# bench_select.tcl: molscope's side of the selection benchmark. Loads the PDB named by
# $env(BENCH_PDB), then for each selection in bench_select.sels (one per line: a label, a
# tab, the VMD selection text) prints "label<TAB>best milliseconds<TAB>atom count", the
# best of $env(BENCH_REPEAT) runs. Each run creates the selection object (compile, evaluate,
# index list) and deletes it.
set t0 [clock microseconds]
mol new $env(BENCH_PDB) waitfor all
puts [format "load\t%.1f\t%d" [expr {([clock microseconds] - $t0) / 1e3}] [molinfo top get numatoms]]
set f [open [file join [file dirname [info script]] bench_select.sels]]
set lines [split [read $f] \n]
close $f
foreach line $lines {
    if {$line eq "" || [string index $line 0] eq "#"} continue
    lassign [split $line \t] label text
    set best 1e99
    for {set r 0} {$r < $env(BENCH_REPEAT)} {incr r} {
        set t0 [clock microseconds]
        set s [atomselect top $text]
        set n [$s num]
        set dt [expr {([clock microseconds] - $t0) / 1e3}]
        $s delete
        if {$dt < $best} { set best $dt }
    }
    puts [format "%s\t%.2f\t%d" $label $best $n]
}
quit
