# pkgIndex.tcl: the viewchangerender package (VMD's ViewChangeRender, ::VCR::) under VMD's
# name and version.
package ifneeded viewchangerender 1.8 [list source [file join $dir viewchangerender.tcl]]
