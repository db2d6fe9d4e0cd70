# tcl: the Tcl library shipped with molscope.
tcllib_DATA += tcl/init.tcl tcl/vectors.tcl
