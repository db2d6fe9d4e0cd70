# pbctools.tcl: the Tcl half of molscope's pbctools (VMD's package of the same name and
# version; doc/pbctools.md). The `pbc` command itself is C (src/commands/cmd_pbc.c: set,
# get, wrap, unwrap, join run over the frames in C); this file holds the subcommands that
# are file reading or drawing: `pbc readxst` (NAMD .xst/.xsc cells), `pbc box_draw` (a
# static box of user graphics) and `pbc box` (a box redrawn whenever the molecule's frame
# changes, through a trace on vmd_frame, as VMD's does), plus VMD's ::PBCTools::pbc* procs.
package provide pbctools 2.8

namespace eval ::PBCTools {
    namespace export pbc*
    # pbc box: per molecule, the options it was drawn with and its graphics ids
    variable box_opts
    variable box_ids
}

foreach ::PBCTools::sub {set get wrap unwrap join} {
    proc ::PBCTools::pbc$::PBCTools::sub {args} "pbc $::PBCTools::sub {*}\$args"
}
unset ::PBCTools::sub

# Options "-name value" and flags of a Tcl subcommand into the array named by arrname;
# spec is a dict: option -> "flag" or "value". Errors read "pbc <sub>: ...".
proc ::PBCTools::options {sub spec words arrname} {
    upvar 1 $arrname o
    for {set i 0} {$i < [llength $words]} {incr i} {
        set w [lindex $words $i]
        set name [string tolower $w]
        if {![dict exists $spec $name]} {
            error "pbc $sub: unknown option \"$w\": must be [join [lsort [dict keys $spec]] {, }]"
        }
        if {[dict get $spec $name] eq "flag"} {
            set o($name) 1
        } elseif {$i + 1 >= [llength $words]} {
            error "pbc $sub: no value for option \"$w\""
        } else {
            set o($name) [lindex $words [incr i]]
        }
    }
}

proc ::PBCTools::number {sub what value {min ""}} {
    if {![string is double -strict $value] || ($min ne "" && $value < $min)} {
        error "pbc $sub: bad value '$value' for $what: must be a number[expr {$min ne {} ? " of at least $min" : {}}]"
    }
    return $value
}

# ---------------------------------------------------------------- readxst

# The cells of an XST/XSC file: a list of {step {A B C}}, lines of numbers "step ax ay az bx
# by bz cx cy cz ox oy oz ...", comments (#) and blank lines skipped.
proc ::PBCTools::xst_cells {file} {
    if {[catch {open $file r} f]} { error "pbc readxst: cannot open \"$file\": $f" }
    set cells {}
    set n 0
    while {[gets $f line] >= 0} {
        incr n
        set line [string trim $line]
        if {$line eq "" || [string index $line 0] eq "#"} continue
        if {[catch {llength $line} k] || $k < 10 ||
            [llength [lmap v [lrange $line 0 9] {expr {[string is double -strict $v] ? $v : [continue]}}]] != 10} {
            close $f
            error "pbc readxst: $file: line $n: expected a step and three cell vectors (10 numbers), got \"[string range $line 0 60]\""
        }
        lassign $line step ax ay az bx by bz cx cy cz
        lappend cells [list $step [list [list $ax $ay $az] [list $bx $by $bz] [list $cx $cy $cz]]]
    }
    close $f
    if {![llength $cells]} { error "pbc readxst: $file: no cell in the file" }
    return $cells
}

# pbc readxst file ?-molid m? ?-first f? ?-last l? ?-all? ?-now? ?-stride n? ?-skipfirst?
#                  ?-step2frame n? ?-log file?
proc ::PBCTools::pbcreadxst {file args} {
    ::PBCTools::options readxst {-molid value -first value -last value -all flag -allframes flag
        -now flag -stride value -skipfirst flag -step2frame value -log value} $args o
    set cells [::PBCTools::xst_cells $file]
    if {[info exists o(-skipfirst)]} { set cells [lrange $cells 1 end] }
    set stride [expr {[info exists o(-stride)] ? [::PBCTools::number readxst -stride $o(-stride) 1] : 1}]
    set molid [::PBCTools::molid readxst [expr {[info exists o(-molid)] ? $o(-molid) : "top"}]]
    set first 0
    set last [expr {[molinfo $molid get numframes] - 1}]
    if {[info exists o(-now)]} { set first [set last [molinfo $molid get frame]] }
    if {[info exists o(-first)]} { set first [::PBCTools::frame_of $molid $o(-first)] }
    if {[info exists o(-last)]} { set last [::PBCTools::frame_of $molid $o(-last)] }
    if {$last < 0 || $first > $last} { error "pbc readxst: no frames to set (frames $first to $last of molecule $molid)" }
    set kept {}
    for {set i 0} {$i < [llength $cells]} {incr i $stride} { lappend kept [lindex $cells $i] }
    if {[info exists o(-step2frame)]} {
        set per [::PBCTools::number readxst -step2frame $o(-step2frame)]
        if {$per <= 0} { error "pbc readxst: bad value '$per' for -step2frame: must be above 0" }
        set n 0
        foreach c $kept {
            set f [expr {int(round([lindex $c 0] / double($per)))}]
            if {$f < $first || $f > $last} continue
            pbc set [lindex $c 1] -namd -molid $molid -first $f -last $f
            incr n
        }
    } else {
        set kept [lrange $kept 0 [expr {$last - $first}]]
        set n [llength $kept]
        if {!$n} { error "pbc readxst: $file: no cell left to set" }
        pbc set [lmap c $kept {lindex $c 1}] -namd -molid $molid -first $first -last [expr {$first + $n - 1}]
    }
    if {[info exists o(-log)]} {
        if {[catch {open $o(-log) w} lf]} { error "pbc readxst: cannot write \"$o(-log)\": $lf" }
        puts $lf "pbc readxst: $n cells from $file set from frame $first"
        close $lf
    }
    return $n
}

# A frame word (a number, first, last, now) as a number.
proc ::PBCTools::frame_of {molid w} {
    switch -- [string tolower $w] {
        first { return 0 }
        last { return [expr {[molinfo $molid get numframes] - 1}] }
        now { return [molinfo $molid get frame] }
    }
    if {![string is integer -strict $w] || $w < 0} {
        error "pbc readxst: bad value '$w' for frame: must be first, last, now, or an integer"
    }
    if {$w >= [molinfo $molid get numframes]} { error "pbc readxst: molecule $molid has no frame $w" }
    return $w
}

# A molecule id (or top) that exists, as a number.
proc ::PBCTools::molid {sub w} {
    if {[string tolower $w] eq "top"} { set w [molinfo top] }
    if {![string is integer -strict $w] || [lsearch -exact [molinfo list] $w] < 0} {
        error "pbc $sub: no molecule '$w'"
    }
    return $w
}

# ---------------------------------------------------------------- box_draw and box

set ::PBCTools::box_spec {-molid value -parallelepiped flag -orthorhombic flag -rectangular flag
    -style value -color value -material value -width value -resolution value -center value
    -centersel value -shiftcenter value -shiftcenterrel value -shift value}

# The corner the box starts from and its three edge vectors, for the molecule's current
# frame and the options in the array named by arrname.
proc ::PBCTools::box_geometry {sub molid arrname} {
    upvar 1 $arrname o
    lassign [lindex [pbc get -namd -now -molid $molid] 0] A B C
    if {[veclength $A] == 0} { error "pbc $sub: molecule $molid has no unit cell in its current frame: set one with pbc set" }
    set center [::PBCTools::box_center $sub $molid $A $B $C o]
    if {[info exists o(-orthorhombic)] || [info exists o(-rectangular)]} {
        set A [list [lindex $A 0] 0 0]; set B [list 0 [lindex $B 1] 0]; set C [list 0 0 [lindex $C 2]]
    }
    list [vecsub $center [vecscale 0.5 [vecadd $A $B $C]]] $A $B $C
}

proc ::PBCTools::box_center {sub molid A B C arrname} {
    upvar 1 $arrname o
    set how [expr {[info exists o(-center)] ? [string tolower $o(-center)] : "unitcell"}]
    set text [expr {[info exists o(-centersel)] ? $o(-centersel) : "all"}]
    switch -- $how {
        unitcell { set c [vecscale 0.5 [vecadd $A $B $C]] }
        origin { set c {0 0 0} }
        com - centerofmass - bb - boundingbox {
            set sel [atomselect $molid $text]
            set bad [catch {
                if {[string match b* $how]} {
                    lassign [measure minmax $sel] lo hi
                    set c [vecscale 0.5 [vecadd $lo $hi]]
                } else {
                    set c [measure center $sel weight mass]
                }
            } err]
            $sel delete
            if {$bad} { error "pbc $sub: -center $how of \"$text\": $err" }
        }
        default { error "pbc $sub: bad value '$o(-center)' for -center: must be unitcell, origin, com, centerofmass, bb, or boundingbox" }
    }
    foreach opt {-shiftcenter -shift} {
        if {[info exists o($opt)]} { set c [vecadd $c [::PBCTools::vec3 $sub $opt $o($opt)]] }
    }
    if {[info exists o(-shiftcenterrel)]} {
        lassign [::PBCTools::vec3 $sub -shiftcenterrel $o(-shiftcenterrel)] i j k
        set c [vecadd $c [vecscale $i $A] [vecscale $j $B] [vecscale $k $C]]
    }
    return $c
}

proc ::PBCTools::vec3 {sub what v} {
    if {[catch {llength $v} n] || $n != 3 || [llength [lmap x $v {expr {[string is double -strict $x] ? $x : [continue]}}]] != 3} {
        error "pbc $sub: bad value '$v' for $what: must be three numbers"
    }
    return $v
}

# Draw the box into molecule molid's user graphics; returns the graphics ids.
proc ::PBCTools::box_items {sub molid arrname} {
    upvar 1 $arrname o
    set style [string tolower [expr {[info exists o(-style)] ? $o(-style) : "lines"}]]
    if {$style ni {lines dashed arrows tubes}} {
        error "pbc $sub: bad value '$o(-style)' for -style: must be lines, dashed, arrows, or tubes"
    }
    set width [::PBCTools::number $sub -width [expr {[info exists o(-width)] ? $o(-width) : 3}] 0]
    set res [::PBCTools::number $sub -resolution [expr {[info exists o(-resolution)] ? $o(-resolution) : 8}] 1]
    lassign [::PBCTools::box_geometry $sub $molid o] p A B C
    set ids [list [graphics $molid color [expr {[info exists o(-color)] ? $o(-color) : "blue"}]]]
    if {[info exists o(-material)]} { lappend ids [graphics $molid material $o(-material)] }
    set r [expr {0.1 * $width}]
    if {$style eq "arrows"} {
        foreach v [list $A $B $C] {
            set tip [vecadd $p $v]
            set base [vecadd $p [vecscale [expr {1 - 4 * $r / [veclength $v]}] $v]]
            lappend ids [graphics $molid cylinder $p $base radius $r resolution $res filled yes]
            lappend ids [graphics $molid cone $base $tip radius [expr {2 * $r}] resolution $res]
        }
        return $ids
    }
    set corners {}
    foreach i {0 1} { foreach j {0 1} { foreach k {0 1} {
        lappend corners [vecadd $p [vecscale $i $A] [vecscale $j $B] [vecscale $k $C]]
    } } }
    # the twelve edges: corner pairs differing in one of i j k (bits 4 2 1)
    foreach {a b} {0 4 1 5 2 6 3 7 0 2 1 3 4 6 5 7 0 1 2 3 4 5 6 7} {
        set u [lindex $corners $a]; set v [lindex $corners $b]
        switch -- $style {
            lines { lappend ids [graphics $molid line $u $v width [expr {max(1, int($width))}] style solid] }
            dashed { lappend ids [graphics $molid line $u $v width [expr {max(1, int($width))}] style dashed] }
            tubes { lappend ids [graphics $molid cylinder $u $v radius $r resolution $res filled no] }
        }
    }
    if {$style eq "tubes"} {
        foreach c $corners { lappend ids [graphics $molid sphere $c radius $r resolution $res] }
    }
    return $ids
}

# pbc box_draw ?options?: a static box; returns the ids of its graphics items.
proc ::PBCTools::pbcbox_draw {args} {
    ::PBCTools::options box_draw $::PBCTools::box_spec $args o
    set molid [::PBCTools::molid box_draw [expr {[info exists o(-molid)] ? $o(-molid) : "top"}]]
    ::PBCTools::box_items box_draw $molid o
}

# pbc box ?-on|-off|-toggle? ?options?: the box of molecule molid, redrawn whenever its
# frame changes.
proc ::PBCTools::pbcbox {args} {
    variable box_opts
    variable box_ids
    set spec [dict merge $::PBCTools::box_spec {-on flag -off flag -toggle flag}]
    ::PBCTools::options box $spec $args o
    set molid [::PBCTools::molid box [expr {[info exists o(-molid)] ? $o(-molid) : "top"}]]
    set on [expr {![info exists o(-off)]}]
    if {[info exists o(-toggle)]} { set on [expr {![info exists box_opts($molid)]}] }
    if {!$on} { ::PBCTools::box_off $molid; return }
    foreach opt {-on -off -toggle} { unset -nocomplain o($opt) }
    set o(-molid) $molid
    # drawn first, so bad options leave the old box as it was
    set ids [::PBCTools::box_items box $molid o]
    ::PBCTools::box_off $molid
    set box_ids($molid) $ids
    set box_opts($molid) [array get o]
    trace add variable ::vmd_frame($molid) write ::PBCTools::box_update
    return
}

proc ::PBCTools::box_draw_now {molid opts} {
    variable box_ids
    array set o $opts
    set box_ids($molid) [::PBCTools::box_items box $molid o]
}

proc ::PBCTools::box_off {molid} {
    variable box_opts
    variable box_ids
    trace remove variable ::vmd_frame($molid) write ::PBCTools::box_update
    if {[info exists box_ids($molid)] && [lsearch -exact [molinfo list] $molid] >= 0} {
        foreach id $box_ids($molid) { graphics $molid delete $id }
    }
    unset -nocomplain box_ids($molid) box_opts($molid)
}

# The trace on vmd_frame(molid): draw the box again for the new frame.
proc ::PBCTools::box_update {name molid op} {
    variable box_opts
    variable box_ids
    if {![info exists box_opts($molid)]} return
    if {[lsearch -exact [molinfo list] $molid] < 0} { ::PBCTools::box_off $molid; return }
    foreach id $box_ids($molid) { graphics $molid delete $id }
    ::PBCTools::box_draw_now $molid $box_opts($molid)
}
