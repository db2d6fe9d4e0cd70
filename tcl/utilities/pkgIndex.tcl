# pkgIndex.tcl: the utilities package (VMD's name and version): ::util:: procedures.
package ifneeded utilities 1.2 [list source [file join $dir utilities.tcl]]
