# topotools.tcl: molscope's topotools package (`package require topotools`), written from
# VMD's topotools documentation: the `topo` command (bonds, angles, dihedrals and impropers
# with their types; guessing terms and atom attributes; LAMMPS data files) and
# ::TopoTools::mergemols, selections2mol and replicatemol. The per-bond and per-term work is
# C (::molscope::topo, src/commands/cmd_topo.c); this file reads VMD's options (-molid,
# -sel, -bondtype, -bondorder, -angletype, -dihedraltype, -impropertype) and makes the
# selection the C side works on. What is and is not implemented: doc/topotools.md.

namespace eval ::TopoTools {
    variable version 1.8
    namespace export topo
}

proc ::TopoTools::usage {} {
    return "usage: topo ?-molid <id>? ?-sel <selection>? <command> ?<args>?
commands: numatoms numatomtypes atomtypenames guessatom <what> <from>
  numbonds numbondtypes bondtypenames getbondlist ?type|order|both|none?
  setbondlist <flag> <list> addbond <i> <j> delbond <i> <j> clearbonds retypebonds
  the same for angles, dihedrals and impropers (numangles getanglelist setanglelist
  addangle delangle clearangles angletypenames retypeangles ...), guessangles
  guessdihedrals guessimpropers ?tolerance <degrees>?
  readlammpsdata <file> ?<atom style>? writelammpsdata <file> ?<atom style>?"
}

# The molecule id of a -molid word ("top" or a number).
proc ::TopoTools::molid {word} {
    if {[molinfo num] == 0} {
        error "topo: no molecule loaded"
    }
    if {$word eq "top"} {
        return [molinfo top]
    }
    if {[lsearch -exact [molinfo list] $word] < 0} {
        error "topo: bad molecule id '$word'"
    }
    return $word
}

# Split the arguments into VMD's options (into the array named by optvar) and the rest.
proc ::TopoTools::options {arglist optvar} {
    upvar 1 $optvar opt
    array set opt {-molid top -sel all -bondtype "" -bondorder 1.0 -angletype ""
        -dihedraltype "" -impropertype "" -tolerance 5.0}
    set rest {}
    for {set i 0} {$i < [llength $arglist]} {incr i} {
        set a [lindex $arglist $i]
        if {[info exists opt($a)] || $a eq "tolerance"} {
            if {$i + 1 >= [llength $arglist]} {
                error "topo: no value for option \"$a\""
            }
            if {$a eq "tolerance"} {
                set a -tolerance
            }
            set opt($a) [lindex $arglist [incr i]]
        } else {
            lappend rest $a
        }
    }
    return $rest
}

# The term kind of a command word, for the -<kind>type option of add<kind>.
proc ::TopoTools::typeoption {cmd} {
    foreach k {angle dihedral improper} {
        if {[string match "add$k" $cmd]} {
            return -${k}type
        }
    }
    return ""
}

proc ::TopoTools::topo {args} {
    set rest [options $args opt]
    if {[llength $rest] == 0} {
        error [usage]
    }
    set cmd [lindex $rest 0]
    set rest [lrange $rest 1 end]
    switch -- $cmd {
        help { return [usage] }
        readlammpsdata { return [readlammpsdata {*}$rest] }
    }
    set sel [atomselect [molid $opt(-molid)] $opt(-sel)]
    try {
        return [run $sel $cmd $rest opt]
    } finally {
        $sel delete
    }
}

# One command on a selection.
proc ::TopoTools::run {sel cmd rest optvar} {
    upvar 1 $optvar opt
    switch -- $cmd {
        numatoms { return [$sel num] }
        atomtypenames { return [lsort -unique [$sel get type]] }
        numatomtypes { return [llength [lsort -unique [$sel get type]]] }
        numbondtypes - numangletypes - numdihedraltypes - numimpropertypes {
            set k [string range $cmd 3 end-5]
            return [llength [::molscope::topo ${k}typenames $sel]]
        }
        addbond {
            if {[llength $rest] != 2} {
                error "topo addbond: wrong # args: usage: topo addbond <i> <j> ?-bondtype <type>? ?-bondorder <order>?"
            }
            return [::molscope::topo addbond $sel {*}$rest $opt(-bondtype) $opt(-bondorder)]
        }
        addangle - adddihedral - addimproper {
            set w [expr {$cmd eq "addangle" ? 3 : 4}]
            if {[llength $rest] == $w} {
                lappend rest [expr {$opt([typeoption $cmd]) eq "" ? "unknown" : $opt([typeoption $cmd])}]
            }
            return [::molscope::topo $cmd $sel {*}$rest]
        }
        guessimpropers { return [::molscope::topo guessimpropers $sel $opt(-tolerance)] }
        writelammpsdata { return [writelammpsdata $sel {*}$rest] }
        default {
            if {[catch {::molscope::topo $cmd $sel {*}$rest} result]} {
                regsub {^::molscope::topo} $result topo result
                if {[string match "*unknown subcommand*" $result]} {
                    regsub {: must be [^:]*$} $result ": must be one of the commands of 'topo help'" result
                }
                error $result
            }
            return $result
        }
    }
}

proc ::TopoTools::readlammpsdata {args} {
    if {[llength $args] < 1 || [llength $args] > 2} {
        error "topo readlammpsdata: wrong # args: usage: topo readlammpsdata <file> ?<atom style>?"
    }
    lassign $args file style
    if {$style eq ""} {
        set style auto
    }
    return [::molscope::topo readdata $file $style]
}

proc ::TopoTools::writelammpsdata {sel args} {
    if {[llength $args] < 1 || [llength $args] > 2} {
        error "topo writelammpsdata: wrong # args: usage: topo writelammpsdata <file> ?<atom style>?"
    }
    lassign $args file style
    if {$style eq ""} {
        set style full
    }
    return [::molscope::topo writedata $sel $file $style]
}

# A new molecule of every atom of the molecules given (all frames when they have as many).
proc ::TopoTools::mergemols {mids} {
    set sels {}
    try {
        foreach m $mids {
            lappend sels [atomselect [molid $m] all]
        }
        return [::molscope::topo combine $sels 1]
    } finally {
        foreach s $sels {
            $s delete
        }
    }
}

# A new molecule of the atoms of the selections given, each at its own frame.
proc ::TopoTools::selections2mol {sels} {
    return [::molscope::topo combine $sels 0]
}

# A new molecule of nx x ny x nz copies of a molecule along its unit cell vectors.
proc ::TopoTools::replicatemol {mol nx ny nz} {
    set sel [atomselect [molid $mol] all]
    try {
        return [::molscope::topo replicate $sel $nx $ny $nz]
    } finally {
        $sel delete
    }
}

proc topo {args} {
    return [uplevel 1 [list ::TopoTools::topo {*}$args]]
}

package provide topotools $::TopoTools::version
