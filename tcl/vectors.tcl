# vectors.tcl: VMD's Tcl-level transformation helpers. The vector and matrix commands that
# scripts call in loops (vecadd ... transmult, transabout, vectrans, coordtrans) are C
# (src/commands/cmd_vector.c); these build matrices from angles and offsets:
#
#   find_rotation_value varname   pop "amount ?deg|rad|pi?" off a list, return radians
#   transaxis x|y|z amount ?deg|rad|pi?      rotation about a coordinate axis
#   transoffset {x y z}                      translation
#   trans ?center v? ?origin v? ?offset v? ?x|y|z|axis a amount ?unit??
#         ?bond v1 v2 amount ?unit?? ?angle v1 v2 v3 amount ?unit??
#   trans_from_rotate, trans_to_rotate, trans_from_offset, trans_to_offset
#
# Matrices are {{r0} {r1} {r2} {r3}}, row-major, acting on column vectors. Angles are in
# degrees unless a unit follows.

set M_PI 3.14159265358979323846

# Remove the amount (and its unit, when one follows) from the front of the list in the
# caller's variable; return the angle in radians.
proc find_rotation_value {varname} {
    upvar 1 $varname words
    if {![info exists words]} {
        error "find_rotation_value: no variable '$varname'"
    }
    set amount [lindex $words 0]
    if {![string is double -strict $amount]} {
        error "find_rotation_value: expected an angle, got '$amount'"
    }
    set unit [lindex $words 1]
    set words [lrange $words 1 end]
    switch -- $unit {
        rad - radian - radians { set scale 1.0 }
        pi { set scale $::M_PI }
        deg - degree - degrees { set scale [expr {$::M_PI / 180.0}] }
        default { return [expr {$amount * $::M_PI / 180.0}] }
    }
    set words [lrange $words 1 end]
    return [expr {$amount * $scale}]
}

proc transaxis {axis args} {
    if {$axis ni {x y z}} {
        error "transaxis: axis must be x, y or z, not '$axis'"
    }
    set a [find_rotation_value args]
    if {[llength $args]} {
        error "transaxis: unknown angle unit '[join $args]': must be deg, rad or pi"
    }
    set c [expr {cos($a)}]
    set s [expr {sin($a)}]
    set ms [expr {-$s}]
    switch $axis {
        x { return [list {1.0 0.0 0.0 0.0} [list 0.0 $c $ms 0.0] [list 0.0 $s $c 0.0] {0.0 0.0 0.0 1.0}] }
        y { return [list [list $c 0.0 $s 0.0] {0.0 1.0 0.0 0.0} [list $ms 0.0 $c 0.0] {0.0 0.0 0.0 1.0}] }
        z { return [list [list $c $ms 0.0 0.0] [list $s $c 0.0 0.0] {0.0 0.0 1.0 0.0} {0.0 0.0 0.0 1.0}] }
    }
}

proc transoffset {v} {
    if {[llength $v] != 3} {
        error "transoffset: expected a vector {x y z}, got '$v'"
    }
    lassign $v x y z
    return [list [list 1.0 0.0 0.0 $x] [list 0.0 1.0 0.0 $y] [list 0.0 0.0 1.0 $z] {0.0 0.0 0.0 1.0}]
}

# The axis of trans's "angle v1 v2 v3": normal to the plane of the three points, or x (z
# when the first leg lies along x) for points in a line.
proc ::molscope::angle_axis {v1 v2 v3} {
    set axis [veccross [vecsub $v2 $v1] [vecsub $v3 $v2]]
    if {[veclength $axis] > 0.0} {
        return [vecnorm $axis]
    }
    if {[veclength [veccross [vecnorm [vecsub $v1 $v2]] {1.0 0.0 0.0}]] < 0.01} {
        puts "Warning: trans found a degenerate 'angle'; using the z axis"
        return {0.0 0.0 1.0}
    }
    puts "Warning: trans found a degenerate 'angle'; using the x axis"
    return {1.0 0.0 0.0}
}

# offset * rotation * (translation by -origin): rotate about `origin`, then move it to
# `offset`. Rotations about axes accumulate (the later one applied last); bond and angle
# set the rotation and the centre from their points.
proc trans {args} {
    set origin {0.0 0.0 0.0}
    set offset {0.0 0.0 0.0}
    set rot [transidentity]
    while {[llength $args]} {
        set args [lassign $args key]
        switch -- $key {
            origin { set args [lassign $args origin] }
            offset { set args [lassign $args offset] }
            center {
                set args [lassign $args offset]
                set origin $offset
            }
            x - y - z - axis {
                if {$key eq "axis"} { set args [lassign $args key] }
                switch -- $key {
                    x { set axis {1.0 0.0 0.0} }
                    y { set axis {0.0 1.0 0.0} }
                    z { set axis {0.0 0.0 1.0} }
                    default {
                        if {[llength $key] != 3} {
                            error "trans: axis must be x, y, z or a vector, not '$key'"
                        }
                        set axis $key
                    }
                }
                set rot [transmult [transabout $axis [find_rotation_value args] rad] $rot]
            }
            bond {
                set args [lassign $args v1 v2]
                set origin $v1
                set offset $v1
                set rot [transabout [vecsub $v2 $v1] [find_rotation_value args] rad]
            }
            angle {
                set args [lassign $args v1 v2 v3]
                set origin $v2
                set offset $v2
                set rot [transabout [::molscope::angle_axis $v1 $v2 $v3] [find_rotation_value args] rad]
            }
            default {
                error "trans: unknown keyword '$key': must be center, origin, offset, x, y, z, axis, bond or angle"
            }
        }
    }
    return [transmult [transoffset $offset] $rot [transoffset [vecinvert $origin]]]
}

proc trans_from_rotate {rotate} {
    lassign $rotate a b c
    return [list [concat $a 0] [concat $b 0] [concat $c 0] {0 0 0 1}]
}

proc trans_to_rotate {m} {
    lassign $m a b c
    return [list [lrange $a 0 2] [lrange $b 0 2] [lrange $c 0 2]]
}

proc trans_from_offset {offset} {
    return [transoffset $offset]
}

proc trans_to_offset {m} {
    return [coordtrans $m {0 0 0}]
}
