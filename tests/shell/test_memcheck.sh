# test_memcheck.sh: a session that crosses most modules (loading, selections with within
# and same-as, measure, every kind of representation, the file renderers and the ray
# tracer, deleting) under valgrind's memcheck: no read of uninitialised memory, no invalid
# access, no definite leak. The offscreen OpenGL device is left out: Mesa's own driver
# leaks a block of its own. Skipped where valgrind is not installed.
. "$(dirname "$0")/lib.sh"
data=$(cd "$(dirname "$0")/../data" && pwd)
if ! command -v valgrind >/dev/null; then
    skip "memcheck session" "valgrind is not installed"; rm -rf "$scratch"; exit 0
fi
cd "$scratch"
cat > session.tcl <<TCL
set m [mol new $data/pept.pdb waitfor all]
animate dup \$m
mol modstyle 0 \$m Licorice
foreach style {VDW CPK Lines Bonds Trace Tube NewCartoon NewRibbons QuickSurf Points} {
    mol representation \$style
    mol addrep \$m
}
set s [atomselect \$m "protein and within 5 of resid 3"]
set t [atomselect \$m "same residue as (name CA and x > 0)"]
puts "[\$s num] [\$t num]"
puts [measure center \$s]
puts [measure rgyr \$s]
puts [measure sasa 1.4 \$t]
\$s delete
\$t delete
display resize 48 36
render TachyonInternal ti.tga
render Tachyon scene.dat
render POV3 scene.pov
render Wavefront scene.obj
mol delete \$m
quit
TCL
MOLSCOPE_THREADS=2 valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
    --show-leak-kinds=definite "$MOLSCOPE" -dispdev text < session.tcl > out.txt 2> vg.txt
rc=$?
summary=$(grep -E "ERROR SUMMARY" vg.txt | sed 's/^==[0-9]*== //')
if [ $rc = 0 ] && [ -s ti.tga ]; then
    pass "memcheck session: $summary"
else
    fail "memcheck session" "exit $rc: $summary; $(grep -m1 -A6 -E 'uninitialised|Invalid|definitely lost in' vg.txt | sed 's/^==[0-9]*== //' | tr '\n' ' ')"
fi
rm -rf "$scratch"
