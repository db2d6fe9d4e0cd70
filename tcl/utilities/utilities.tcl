# utilities.tcl: the `utilities` package under VMD's name and version, molscope's own code
# for the ::util:: procedures VMD's plugins and users' scripts call: angles, rounding,
# quaternions (the viewpoint interpolation of viewchangerender), option lists, list
# operations and bond lists. doc/viewchangerender.md lists what is here and what is not.
package provide utilities 1.2

namespace eval ::util {
    namespace export *
}

# ---------------------------------------------------------------- numbers

proc ::util::deg2rad {deg} { expr {$deg * acos(-1) / 180.0} }
proc ::util::rad2deg {rad} { expr {$rad * 180.0 / acos(-1)} }
# The signed arctangent of y/x (Tcl's atan2, with both zero an error as in VMD's).
proc ::util::atan2 {y x} {
    if {$x == 0 && $y == 0} { error "::util::atan2: undefined for x = y = 0" }
    expr {atan2($y, $x)}
}
proc ::util::min {a b} { expr {$a < $b ? $a : $b} }
proc ::util::max {a b} { expr {$a > $b ? $a : $b} }
# Away from zero, and toward zero, to an integer.
proc ::util::roundup {x} { expr {$x > 0 ? int(ceil($x)) : int(floor($x))} }
proc ::util::rounddown {x} { expr {$x < 0 ? int(ceil($x)) : int(floor($x))} }

# ---------------------------------------------------------------- quaternions {w x y z}

# The unit quaternion of the rotation in the upper 3x3 of a 4x4 matrix (rows as VMD's
# matrices), for the convention of ::util::quat2mat. Shepperd's method: the largest of the
# four squared components is computed first, so no division by a small number.
proc ::util::mat2quat {m} {
    lassign [lindex $m 0] a00 a01 a02
    lassign [lindex $m 1] a10 a11 a12
    lassign [lindex $m 2] a20 a21 a22
    set t [expr {$a00 + $a11 + $a22}]
    set big [lsort -real -decreasing -index 0 [list [list $t w] [list $a00 x] [list $a11 y] [list $a22 z]]]
    switch -- [lindex $big 0 1] {
        w {
            set s [expr {2.0 * sqrt(1.0 + $t)}]
            set q [list [expr {0.25 * $s}] [expr {($a12 - $a21) / $s}] \
                       [expr {($a20 - $a02) / $s}] [expr {($a01 - $a10) / $s}]]
        }
        x {
            set s [expr {2.0 * sqrt(1.0 + $a00 - $a11 - $a22)}]
            set q [list [expr {($a12 - $a21) / $s}] [expr {0.25 * $s}] \
                       [expr {($a01 + $a10) / $s}] [expr {($a02 + $a20) / $s}]]
        }
        y {
            set s [expr {2.0 * sqrt(1.0 + $a11 - $a00 - $a22)}]
            set q [list [expr {($a20 - $a02) / $s}] [expr {($a01 + $a10) / $s}] \
                       [expr {0.25 * $s}] [expr {($a12 + $a21) / $s}]]
        }
        z {
            set s [expr {2.0 * sqrt(1.0 + $a22 - $a00 - $a11)}]
            set q [list [expr {($a01 - $a10) / $s}] [expr {($a02 + $a20) / $s}] \
                       [expr {($a12 + $a21) / $s}] [expr {0.25 * $s}]]
        }
    }
    return $q
}

# The 4x4 rotation matrix of a quaternion (normalised first); the inverse of mat2quat.
proc ::util::quat2mat {q} {
    set n [expr {sqrt([vecdot $q $q])}]
    if {$n == 0} { error "::util::quat2mat: the zero quaternion is no rotation" }
    lassign [vecscale [expr {1.0 / $n}] $q] w x y z
    list [list [expr {1 - 2*($y*$y + $z*$z)}] [expr {2*($x*$y + $w*$z)}] [expr {2*($x*$z - $w*$y)}] 0.0] \
         [list [expr {2*($x*$y - $w*$z)}] [expr {1 - 2*($x*$x + $z*$z)}] [expr {2*($y*$z + $w*$x)}] 0.0] \
         [list [expr {2*($x*$z + $w*$y)}] [expr {2*($y*$z - $w*$x)}] [expr {1 - 2*($x*$x + $y*$y)}] 0.0] \
         {0.0 0.0 0.0 1.0}
}

proc ::util::quatinv {q} { vecinvert $q }
proc ::util::quatadd {q1 q2} { vecadd $q1 $q2 }
proc ::util::quatdot {q1 q2} { vecdot $q1 $q2 }

# Spherical linear interpolation from q1 (t = 0) to q2 (t = 1), the short way round.
proc ::util::quatarc {q1 q2 t} {
    set d [expr {[vecdot $q1 $q2] / sqrt([vecdot $q1 $q1] * [vecdot $q2 $q2])}]
    if {$d < 0} {
        set q1 [vecinvert $q1]
        set d [expr {-$d}]
    }
    if {$d > 0.999999} {
        # nearly the same rotation: a straight line is exact enough and avoids sin(0)
        return [vecadd [vecscale [expr {1.0 - $t}] $q1] [vecscale $t $q2]]
    }
    set th [expr {acos($d)}]
    vecadd [vecscale [expr {sin((1.0 - $t) * $th) / sin($th)}] $q1] \
           [vecscale [expr {sin($t * $th) / sin($th)}] $q2]
}

# The rotation a fraction t of the way from matrix mi to matrix mf.
proc ::util::quatinterpmatrices {mi mf t} {
    quat2mat [quatarc [mat2quat $mi] [mat2quat $mf] $t]
}

# ---------------------------------------------------------------- option lists

# The n words after option tag in arglist (joined), deflt when tag is absent; with n 0,
# whether tag is there.
proc ::util::getargs {arglist tag deflt {n 1}} {
    set i [lsearch -exact $arglist $tag]
    if {$n == 0} { return [expr {$i >= 0}] }
    if {$i < 0} { return $deflt }
    join [lrange $arglist $i+1 $i+$n]
}

# deflt when the switch tag is absent, its negation when present.
proc ::util::getswitch {arglist tag {deflt 0}} {
    expr {[lsearch -exact $arglist $tag] < 0 ? $deflt : !$deflt}
}

# ---------------------------------------------------------------- lists

proc ::util::lmin {l} { lindex [lsort -real $l] 0 }
proc ::util::lmax {l} { lindex [lsort -real $l] end }
# Elements of a that are not in b.
proc ::util::ldiff {a b} { ::lmap e $a { if {$e in $b} continue; set e } }
# Elements in only one of a and b.
proc ::util::lnand {a b} { concat [ldiff $a $b] [ldiff $b $a] }
# The distinct elements in both a and b, sorted.
proc ::util::lintersect {a b} {
    lsort -unique [::lmap e $a { if {$e ni $b} continue; set e }]
}
# The last index up to which a and b are equal (-1 when they differ at once).
proc ::util::lcompare {a b} {
    set i -1
    foreach x $a y $b {
        if {$x ne $y} break
        incr i
    }
    return $i
}
# The first run of consecutive elements of b also found consecutively in a; with -all,
# every such run, as a list of lists.
proc ::util::lcontains {a b args} {
    set all [getswitch $args -all]
    set runs {}
    set from 0
    for {set j 0} {$j < [llength $b]} {incr j} {
        set i [lsearch -exact -start $from $a [lindex $b $j]]
        if {$i < 0} continue
        set last [lcompare [lrange $a $i end] [lrange $b $j end]]
        set run [lrange $b $j $j+$last]
        if {!$all} { return $run }
        lappend runs $run
        incr j $last
        set from [expr {$i + $last + 1}]
    }
    return $runs
}
proc ::util::lrevert {l} { lreverse $l }
# Add a to every element of the list in the variable listname; returns the list.
proc ::util::lincr {listname {a 1}} {
    upvar 1 $listname l
    set l [::lmap e $l { expr {$e + $a} }]
}
# list1 ordered as lsort (with args) orders list2; returns both lists so ordered.
proc ::util::sort_alike {list1 list2 args} {
    set key 1
    set i [lsearch -exact $args -index]
    if {$i >= 0} {
        set key [list 1 [lindex $args $i+1]]
        set args [lreplace $args $i $i+1]
    }
    set pairs [::lmap x $list1 y $list2 { list $x $y }]
    set sorted [lsort {*}$args -index $key $pairs]
    list [::lmap p $sorted { lindex $p 0 }] [::lmap p $sorted { lindex $p 1 }]
}
# Each element through a script that reads it as $elem.
proc ::util::lmap {inlist expression} {
    set out {}
    foreach elem $inlist { lappend out [eval $expression] }
    return $out
}

# ---------------------------------------------------------------- bonds

proc ::util::factorial {n} {
    set f 1
    for {set i 2} {$i <= $n} {incr i} { set f [expr {$f * $i}] }
    return $f
}

# The selection of -sel, or every atom of -molid (top), made in the caller's frame (a
# selection lives as long as the procedure that made it).
proc ::util::bond_sel {arglist} {
    set sel [getargs $arglist -sel {}]
    if {$sel ne ""} { return $sel }
    uplevel 1 [list atomselect [getargs $arglist -molid top] all]
}

# Bonded pairs {i j} (i < j) of the atoms of -sel or of -molid, sorted.
proc ::util::bondlist {args} {
    set sel [bond_sel $args]
    set pairs {}
    foreach i [$sel list] partners [$sel getbonds] {
        foreach j $partners { lappend pairs [lsort -integer [list $i $j]] }
    }
    lsort -dictionary -unique $pairs
}

# Angles {a b c} (b the centre, each once, a < c) from the bonds of -sel or of -molid.
proc ::util::anglelist {args} {
    set sel [bond_sel $args]
    set angles {}
    foreach b [$sel list] partners [$sel getbonds] {
        set partners [lsort -integer -unique $partners]
        for {set i 0} {$i < [llength $partners]} {incr i} {
            foreach c [lrange $partners $i+1 end] {
                lappend angles [list [lindex $partners $i] $b $c]
            }
        }
    }
    lsort -dictionary $angles
}

# Remove every bond of molecule molid.
proc ::util::clear_bondlist {molid} {
    set sel [atomselect $molid all]
    $sel setbonds [lrepeat [$sel num] {}]
    $sel delete
}

# Bond atoms i and j of molid unless they are bonded: 1 when they were, else 0.
proc ::util::addbond {molid i j} {
    set sel [atomselect $molid all]
    set bonds [$sel getbonds]
    set had [expr {$j in [lindex $bonds $i] && $i in [lindex $bonds $j]}]
    if {!$had} {
        if {$j ni [lindex $bonds $i]} { lset bonds $i [concat [lindex $bonds $i] $j] }
        if {$i ni [lindex $bonds $j]} { lset bonds $j [concat [lindex $bonds $j] $i] }
        $sel setbonds $bonds
    }
    $sel delete
    return $had
}

# Remove the bond between atoms i and j of molid: 1 when there was one, else 0.
proc ::util::delbond {molid i j} {
    set sel [atomselect $molid all]
    set bonds [$sel getbonds]
    set had [expr {$j in [lindex $bonds $i] && $i in [lindex $bonds $j]}]
    lset bonds $i [ldiff [lindex $bonds $i] $j]
    lset bonds $j [ldiff [lindex $bonds $j] $i]
    $sel setbonds $bonds
    $sel delete
    return $had
}
