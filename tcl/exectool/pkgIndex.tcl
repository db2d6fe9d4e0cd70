# pkgIndex.tcl: molscope's exectool, under VMD's package name and version (doc/exectool.md).
package ifneeded exectool 1.2 [list source [file join $dir exectool.tcl]]
