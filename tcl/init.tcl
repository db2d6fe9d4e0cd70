# init.tcl: molscope's Tcl library, sourced at startup before any file is loaded.
# It sets up the package path and loads the library scripts that define VMD's Tcl-level
# commands; the commands themselves are C (see src/commands).

namespace eval ::molscope {
    variable libdir [file dirname [file normalize [info script]]]
}
if {[lsearch -exact $::auto_path $::molscope::libdir] < 0} {
    lappend ::auto_path $::molscope::libdir
}

# The `parallel` command (VMD's, over MPI) is a package of its own so that a plain tclsh
# under mpirun can load it too. A missing package is reported, not fatal.
if {[catch {package require molscope::parallel} ::molscope::err]} {
    puts stderr "molscope: the parallel command is not available: $::molscope::err"
}
unset -nocomplain ::molscope::err

# Library scripts, in order; each defines procs (vmdplugins.tcl also adds a VMD tree's plugin
# folders to auto_path, after this library).
foreach ::molscope::script {vectors.tcl movie.tcl vmdplugins.tcl} {
    source [file join $::molscope::libdir $::molscope::script]
}
unset -nocomplain ::molscope::script
