# pkgIndex.tcl: molscope's pbctools, under VMD's package name and version so that
# `package require pbctools` lines of VMD scripts load it (doc/pbctools.md).
package ifneeded pbctools 2.8 [list source [file join $dir pbctools.tcl]]
