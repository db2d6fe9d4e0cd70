# bench_select.tcl: molscope's side of the selection benchmark. Loads every PDB named in
# $env(BENCH_PDBS) (one molecule each), then for each selection in bench_select.sels (lines
# "label<TAB>VMD selection text") times it $env(BENCH_REPEAT) times on each molecule in
# turn, so that every size sees the same background load, and prints
# "size<TAB>label<TAB>median ms<TAB>best ms<TAB>atom count". A timing is creating the
# selection object (compile, evaluate, index list); the object is then deleted.
proc median {l} {
    set l [lsort -real $l]
    set n [llength $l]
    expr {$n % 2 ? [lindex $l [expr {$n / 2}]] : ([lindex $l [expr {$n / 2 - 1}]] + [lindex $l [expr {$n / 2}]]) / 2.0}
}
set mols {}
foreach pdb $env(BENCH_PDBS) {
    set t0 [clock microseconds]
    set id [mol new $pdb waitfor all]
    set ms [expr {([clock microseconds] - $t0) / 1e3}]
    lappend mols $id
    puts [format "%d\tload\t%.1f\t%.1f\t%d" [molinfo $id get numatoms] $ms $ms [molinfo $id get numatoms]]
}
set f [open [file join [file dirname [info script]] bench_select.sels]]
set lines [split [read $f] \n]
close $f
foreach line $lines {
    if {$line eq "" || [string index $line 0] eq "#"} continue
    lassign [split $line \t] label text
    foreach id $mols { set times($id) {} }
    for {set r 0} {$r < $env(BENCH_REPEAT)} {incr r} {
        foreach id $mols {
            set t0 [clock microseconds]
            set s [atomselect $id $text]
            set n($id) [$s num]
            lappend times($id) [expr {([clock microseconds] - $t0) / 1e3}]
            $s delete
        }
    }
    foreach id $mols {
        puts [format "%d\t%s\t%.2f\t%.2f\t%d" [molinfo $id get numatoms] $label \
                  [median $times($id)] [tcl::mathfunc::min {*}$times($id)] $n($id)]
    }
}
quit
