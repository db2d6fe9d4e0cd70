# example.tcl: molscope's bundled example. Loads a structure, prints what molscope found in
# it, as a scientist checks a file before a long rendering job, then renders a quick preview
# with the offscreen OpenGL device: every atom a sphere of its element's VMD radius and
# colour, written to example.png (or the file named second).
# Until representations land the spheres are drawn with `graphics` from the file's ATOM and
# HETATM records; `mol addrep` with VDW will replace that.
lassign $argv file png
if {$png eq ""} { set png example.png }
set m [mol new $file waitfor all]
puts [mol list $m]
lassign [molinfo $m get {numatoms numframes}] natoms nframes
puts "center [lindex [molinfo $m get center] 0]"
puts "cell   [molinfo $m get {a b c alpha beta gamma}]"

array set radius {H 1.2 C 1.7 N 1.55 O 1.52 S 1.8 P 1.8}
proc element_color {e} {
    if {[catch {color Element $e} c]} { return ochre }
    return $c
}
set f [open $file]
foreach line [split [read $f] \n] {
    if {![regexp {^(ATOM  |HETATM)} $line]} continue
    set e [string totitle [string trim [string range $line 76 77]]]
    lappend byelement($e) [lmap c [list [string range $line 30 37] [string range $line 38 45] \
                                         [string range $line 46 53]] {string trim $c}]
}
close $f
graphics $m material AOChalky
foreach e [array names byelement] {
    graphics $m color [element_color $e]
    set r [expr {[info exists radius($e)] ? $radius($e) : 1.5}]
    foreach p $byelement($e) { graphics $m sphere $p radius $r resolution 12 }
}
display resetview
display resize 640 640
set n [llength [join [lmap e [array names byelement] {set byelement($e)}]]]
if {[catch {time {render snapshot $png}} t]} {
    puts "no preview image: $t"
} else {
    puts "rendered $n atoms to [file normalize $png] ([join [display get size] x],\
          [format %.2f [expr {[lindex $t 0] / 1e6}]] s)"
}
quit
