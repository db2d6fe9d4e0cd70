# pkgIndex.tcl: the molscope::parallel package (the MPI-aware `parallel` command). Its
# shared library sits beside this file when installed, in .libs/ in the build tree. A plain
# tclsh finds it with `lappend auto_path <molscope's Tcl library>` or TCLLIBPATH.
package ifneeded molscope::parallel 1.0 [list apply {{dir} {
    set so parallel[info sharedlibextension]
    foreach f [list [file join $dir $so] [file join $dir .libs $so]] {
        if {[file exists $f]} {
            load $f Molscope_parallel
            return
        }
    }
    error "molscope::parallel: $so is neither in $dir nor in $dir/.libs"
}} $dir]
