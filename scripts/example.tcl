# example.tcl: molscope's bundled example, the main job. Loads a structure and prints what
# molscope found in it, as a scientist checks a file before a long rendering job; then draws
# it as a VMD script would (a cartoon coloured by secondary structure, the other atoms as
# licorice coloured by element) and renders the scene with Tachyon: the scene file, and a
# PNG when Debian's tachyon is installed.
#   molscope -e example.tcl -args structure.pdb ?output-prefix?
set file [lindex $argv 0]
set out [expr {[llength $argv] > 1 ? [lindex $argv 1] : "example"}]
set m [mol new $file waitfor all]
puts [mol list $m]
lassign [molinfo $m get {numatoms numframes}] natoms nframes
puts "center [lindex [molinfo $m get center] 0]"
puts "cell   [molinfo $m get {a b c alpha beta gamma}]"

mol modstyle 0 $m NewCartoon
mol modcolor 0 $m Structure
mol representation Licorice 0.3
mol selection "not protein"
mol color Element
mol addrep $m
display resize 800 600
file delete $out.png
if {[auto_execok tachyon] ne ""} {
    # tachyon exits 0 even when it cannot read the scene: look for the image
    render Tachyon $out.dat tachyon -aasamples 4 -format PNG -o $out.png %s > /dev/null
    if {![file exists $out.png]} { error "tachyon made no image from $out.dat" }
    puts "rendered $out.png"
} else {
    render Tachyon $out.dat
    puts "wrote $out.dat (Debian's tachyon renders it: tachyon -format PNG -o $out.png $out.dat)"
}
quit
