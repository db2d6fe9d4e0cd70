# test_memlimit.sh: a stage that cannot fit in the memory this process may have is refused
# with a Tcl error naming what it needs and the setting that would make it fit, never a
# crash: molscope runs under an address-space limit (ulimit -v, RLIMIT_AS) of what it maps
# after loading 1tii and a first small render (the tracer's threads started) plus 1 GB, then
# asks for a QuickSurf at a 0.02 A grid and a 30000 x 30000 TachyonInternal image;
# afterwards the molecule still draws at sane settings.
. "$(dirname "$0")/lib.sh"
cd "$scratch"
cat > limit.tcl <<'TCL'
set m [mol new $env(MS_TEST_DATA)/1tii.pdb waitfor all]
proc vm {} {
    set f [open /proc/self/status]; set s [read $f]; close $f
    regexp {VmSize:\s+(\d+)} $s -> kb
    return $kb
}
display resize 64 48
render TachyonInternal first.png
if {[lindex $argv 0] eq "size"} { puts "VMSIZE [vm]"; quit }
mol modstyle 0 $m QuickSurf 1.0 0.5 0.02 0
if {[catch {mol repinfo $m 0} e]} { puts "QS: $e" } else { puts "QS: built" }
mol modstyle 0 $m QuickSurf 1.0 0.5 1.5 0
puts "QS2: [expr {[dict get [mol repinfo $m 0] triangles] > 10000}]"
display resize 30000 30000
if {[catch {render TachyonInternal big.png} e]} { puts "RT: $e" } else { puts "RT: rendered" }
puts "BIG: [file exists big.png]"
display resize 64 48
render TachyonInternal small.png
puts "SMALL: [file exists small.png]"
quit
TCL
M="$MOLSCOPE -dispdev text -e limit.tcl -args"
base=$($M size </dev/null 2>&1 | sed -n 's/^VMSIZE //p')
if [ -z "$base" ]; then fail "molscope reports its mapped size" "no VMSIZE line"; exit 0; fi
out=$( (ulimit -v $((base + 1024 * 1024)); $M run </dev/null 2>&1); echo "status $?")
qs=$(echo "$out" | sed -n 's/^QS: //p')
expect_match "QuickSurf at 0.02 A is refused before allocating, naming a grid spacing that fits" \
    "$qs" "*needs * bytes, more than half the memory budget*grid spacing of about * A instead of 0.02 A would fit*"
expect_eq "the same rep at 1.5 A still builds under the limit" "$(echo "$out" | sed -n 's/^QS2: //p')" 1
expect_match "a 30000x30000 render is refused, naming the image size" \
    "$(echo "$out" | sed -n 's/^RT: //p')" "*30000x30000 image needs * GB*a smaller image (display resize) would fit*"
expect_eq "the refused render leaves no file" "$(echo "$out" | sed -n 's/^BIG: //p')" 0
expect_eq "a small render works afterwards" "$(echo "$out" | sed -n 's/^SMALL: //p')" 1
expect_eq "molscope exits normally (no crash, no OOM kill)" "$(echo "$out" | tail -1)" "status 0"
rm -rf "$scratch"
