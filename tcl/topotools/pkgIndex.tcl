# pkgIndex.tcl: the topotools package (VMD's name and version): the `topo` command and the
# ::TopoTools:: procedures, molscope's own implementation over ::molscope::topo.
package ifneeded topotools 1.8 [list source [file join $dir topotools.tcl]]
