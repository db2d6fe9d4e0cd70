# vmdplugins.tcl: loading VMD's own Tcl plugins. A VMD tree named by MOLSCOPE_VMDPLUGINDIR
# (its plugins folder, or the VMD folder above it) or VMDDIR adds its plugin folders
# (plugins/noarch/tcl and plugins/LINUXAMD64/tcl) to auto_path after molscope's library, so
# `package require` finds VMD's plugins while molscope's own packages of the same version
# (pbctools, exectool) win. vmd_install_extension, which plugins call to put themselves in
# VMD's Extensions menu, records the extension, registers its menu with `menu tk register`
# where the menu command exists, and draws nothing.

namespace eval ::molscope {
    # name -> {proc menupath} of every extension installed
    variable extensions
}

proc vmd_install_extension {name cmd menupath} {
    set ::molscope::extensions($name) [list $cmd $menupath]
    if {[info commands menu] ne ""} { menu tk register $name $cmd $menupath }
    return
}

# The plugin folders of a VMD tree, in the order they are searched.
proc ::molscope::vmd_plugin_dirs {} {
    set roots {}
    if {[info exists ::env(MOLSCOPE_VMDPLUGINDIR)] && $::env(MOLSCOPE_VMDPLUGINDIR) ne ""} {
        set p $::env(MOLSCOPE_VMDPLUGINDIR)
        lappend roots $p [file join $p plugins]
    }
    if {[info exists ::env(VMDDIR)] && $::env(VMDDIR) ne ""} {
        lappend roots [file join $::env(VMDDIR) plugins]
    }
    set dirs {}
    foreach r $roots {
        foreach arch {noarch LINUXAMD64} {
            set d [file join $r $arch tcl]
            if {[file isdirectory $d] && $d ni $dirs} { lappend dirs $d }
        }
    }
    return $dirs
}

foreach ::molscope::dir [::molscope::vmd_plugin_dirs] {
    if {[lsearch -exact $::auto_path $::molscope::dir] < 0} { lappend ::auto_path $::molscope::dir }
}
unset -nocomplain ::molscope::dir
