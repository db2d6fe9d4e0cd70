# example.tcl: molscope's bundled example. Loads a structure and prints what molscope
# found in it, as a scientist checks a file before a long rendering job.
set file [lindex $argv 0]
set m [mol new $file waitfor all]
puts [mol list $m]
lassign [molinfo $m get {numatoms numframes}] natoms nframes
puts "center [lindex [molinfo $m get center] 0]"
puts "cell   [molinfo $m get {a b c alpha beta gamma}]"
quit
