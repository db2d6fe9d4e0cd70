# viewchangerender.tcl: VMD's ViewChangeRender (`package require viewchangerender`, the
# ::VCR:: commands) for scripts, molscope's own code. A viewpoint is every molecule's
# view matrices (molinfo's center_matrix rotate_matrix scale_matrix global_matrix) and
# frame; move_vp goes from one viewpoint to another over N steps (rotation by quaternion
# interpolation, centre, scale and translation linearly, frames through), eased smooth or
# sharp, and renders each step on molscope's movie engine when asked (frames handed out over
# MPI, resumable). doc/viewchangerender.md is the user's page.
package require utilities 1.2
package provide viewchangerender 1.8

namespace eval ::VCR {
    namespace export save_vp retrieve_vp remove_vp list_vps move_vp write_vps
    # viewpoint name -> dict: molecule id -> {center rotate scale global frame}
    variable viewpoints
    array set viewpoints {}
    variable matrices {center_matrix rotate_matrix scale_matrix global_matrix}
    # molscope: where move_vp ... render puts its frames (<basename>.%05d.png) and with what
    variable basename vcr_frame
    variable renderer snapshot
    # molscope: a video of a rendered move ("": frames only; its extension names the format)
    variable video ""
}

proc ::VCR::fail {cmd what} { error "::VCR::$cmd: $what" }

proc ::VCR::known {cmd vp} {
    variable viewpoints
    if {![info exists viewpoints($vp)]} {
        set have [lsort -dictionary [array names viewpoints]]
        fail $cmd "no viewpoint '$vp' (saved: [expr {[llength $have] ? [join $have {, }] : {none}}])"
    }
}

# The current view of every molecule.
proc ::VCR::current {} {
    variable matrices
    set vp {}
    foreach m [molinfo list] {
        dict set vp $m [concat [molinfo $m get $matrices] [molinfo $m get frame]]
    }
    return $vp
}

# Save the current view as viewpoint vp (a new number when none is given); returns its name.
proc ::VCR::save_vp {{vp ""}} {
    variable viewpoints
    if {[molinfo num] == 0} { fail save_vp "no molecule is loaded" }
    if {$vp eq ""} {
        set vp 1
        while {[info exists viewpoints($vp)]} { incr vp }
    }
    set viewpoints($vp) [current]
    return $vp
}

# Set every molecule of a view (a dict as viewpoints holds) that still exists.
proc ::VCR::set_view {view} {
    variable matrices
    dict for {m v} $view {
        if {$m ni [molinfo list]} continue
        molinfo $m set $matrices [lrange $v 0 3]
        set f [lindex $v 4]
        set nf [molinfo $m get numframes]
        if {$nf > 0} { molinfo $m set frame [expr {min(max($f, 0), $nf - 1)}] }
    }
}

proc ::VCR::retrieve_vp {vp} {
    known retrieve_vp $vp
    set_view $::VCR::viewpoints($vp)
    return
}

proc ::VCR::remove_vp {vp} {
    known remove_vp $vp
    unset ::VCR::viewpoints($vp)
    return
}

# The names of the saved viewpoints, in order.
proc ::VCR::list_vps {} {
    lsort -dictionary [array names ::VCR::viewpoints]
}

# ---------------------------------------------------------------- interpolation

# The matrix a fraction s of the way from a to b, element by element.
proc ::VCR::lerp_matrix {a b s} {
    lmap ra $a rb $b { lmap x $ra y $rb { expr {$x + $s * ($y - $x)} } }
}

# One molecule's view a fraction s of the way from v1 to v2.
proc ::VCR::between {v1 v2 s} {
    lassign $v1 c1 r1 k1 g1 f1
    lassign $v2 c2 r2 k2 g2 f2
    list [lerp_matrix $c1 $c2 $s] [::util::quatinterpmatrices $r1 $r2 $s] \
         [lerp_matrix $k1 $k2 $s] [lerp_matrix $g1 $g2 $s] \
         [expr {int(round($f1 + $s * ($f2 - $f1)))}]
}

# The eased fraction of step t (0..1): smooth starts and stops slowly, sharp is linear.
proc ::VCR::ease {t easing} {
    if {$easing eq "sharp"} { return $t }
    expr {(1.0 - cos(acos(-1) * $t)) / 2.0}
}

# The view a fraction s of the way from view a to view b (molecules in only one keep it).
proc ::VCR::view_between {a b s} {
    set out $b
    dict for {m v} $a {
        if {[dict exists $b $m]} { dict set out $m [between $v [dict get $b $m] $s] }
    }
    return $out
}

# Step i (0-based) of n from view a to view b: set the scene (from i alone, so any rank
# can render any step).
proc ::VCR::step {a b n easing i} {
    set_view [view_between $a $b [ease [expr {($i + 1.0) / $n}] $easing]]
}

# move_vp start end ?morph_frames? ?smooth|sharp? ?render?: from viewpoint start ("here":
# the current view) to viewpoint end in morph_frames steps (50), the last being end.
proc ::VCR::move_vp {start end args} {
    set n 50
    set easing smooth
    set render 0
    foreach a $args {
        if {[string is integer -strict $a]} {
            if {$a < 1} { fail move_vp "morph_frames: expected at least 1 step, got $a" }
            set n $a
        } elseif {[string tolower $a] in {smooth sharp}} {
            set easing [string tolower $a]
        } elseif {[string equal -nocase $a render]} {
            set render 1
        } else {
            fail move_vp "unknown argument '$a': must be a step count, smooth, sharp or render"
        }
    }
    set a [expr {$start eq "here" ? [current] : [view_of move_vp $start]}]
    set b [expr {$end eq "here" ? [current] : [view_of move_vp $end]}]
    if {$render} {
        render_move $a $b $n $easing
    } else {
        for {set i 0} {$i < $n} {incr i} {
            step $a $b $n $easing $i
            display update
        }
    }
    set_view $b
    return
}

proc ::VCR::view_of {cmd vp} {
    known $cmd $vp
    return $::VCR::viewpoints($vp)
}

# Render the n steps of a move with `movie make` (collective under MPI).
proc ::VCR::render_move {a b n easing} {
    variable basename
    set o [list -type user -frames $n -basename $basename -renderer $::VCR::renderer \
               -proc [list ::VCR::step $a $b $n $easing]]
    if {$::VCR::video ne ""} { lappend o -video $::VCR::video }
    movie make {*}$o
}

# Write a Tcl file that, sourced, restores the saved viewpoints.
proc ::VCR::write_vps {file} {
    variable viewpoints
    set text "# Viewpoints of ViewChangeRender (::VCR::), written by molscope on\
              [clock format [clock seconds] -format %Y-%m-%d]: source this file to restore them.\n"
    append text "package require viewchangerender\n"
    foreach vp [list_vps] {
        append text [list set ::VCR::viewpoints($vp) $viewpoints($vp)] \n
    }
    set tmp $file.tmp-[pid]
    if {[catch {
        set f [open $tmp w]
        puts -nonewline $f $text
        close $f
        file rename -force $tmp $file
    } msg]} {
        catch {close $f}
        file delete $tmp
        fail write_vps "cannot write $file: $msg"
    }
    return
}
