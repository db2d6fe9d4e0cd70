# bench_util.tcl: what the Tcl sides of the benchmarks share (sourced by bench_reps.tcl and
# bench_twins.tcl).

# The CPU time of this process so far, all threads, in 10 ms ticks (user + system, from
# /proc/self/stat): it varies less than wall time on a busy machine.
proc cputicks {} {
    set f [open /proc/self/stat]
    set s [read $f]
    close $f
    set fields [split [string range $s [expr {[string last ")" $s] + 2}] end]]
    expr {[lindex $fields 11] + [lindex $fields 12]}
}
