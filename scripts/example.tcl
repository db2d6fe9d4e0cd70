# example.tcl: molscope's bundled example, the main job. Loads a structure and prints what
# molscope found in it, as a scientist checks a file before a long rendering job; then draws
# it as a VMD script would (a cartoon coloured by secondary structure, the other atoms as
# licorice coloured by element) and renders a preview with `render snapshot`.
#   molscope -dispdev opengl -e example.tcl -args structure.pdb ?image.png?
lassign $argv file png
if {$png eq ""} { set png example.png }
set m [mol new $file waitfor all]
puts [mol list $m]
set all [atomselect $m all]
puts "residues [llength [lsort -unique -integer [$all get residue]]]\
      fragments [llength [lsort -unique -integer [$all get fragment]]]"
$all delete
puts "center [lindex [molinfo $m get center] 0]"
puts "cell   [molinfo $m get {a b c alpha beta gamma}]"

mol modstyle 0 $m NewCartoon
mol modcolor 0 $m Structure
mol representation Licorice 0.3
mol selection "not protein"
mol color Element
mol addrep $m
display resize 800 600
if {[catch {time {render snapshot $png}} t]} {
    puts "no preview image: $t"
    quit 1
}
puts "rendered [file normalize $png] ([join [display get size] x],\
      [format %.2f [expr {[lindex $t 0] / 1e6}]] s)"
quit
