# pkgIndex.tcl: the vmdmovie package (VMD's MovieMaker, under VMD's name) on molscope's
# movie engine.
package ifneeded vmdmovie 1.9 [list source [file join $dir vmdmovie.tcl]]
