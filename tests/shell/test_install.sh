# test_install.sh: `make install` under a prefix gives a program that finds its plugins
# and Tcl library by itself, with no MOLSCOPE_* variable set.
. "$(dirname "$0")/lib.sh"
prefix="$scratch/prefix"
if ! make -s -C "$MS_BUILDDIR" install prefix="$prefix" > "$scratch/install.log" 2>&1; then
    fail "make install" "$(tail -3 "$scratch/install.log")"
    exit 0
fi
pass "make install"
for f in bin/molscope lib/molscope/plugins/pdb.so share/molscope/tcl/init.tcl \
         share/molscope/tcl/parallel/pkgIndex.tcl share/molscope/tcl/parallel/parallel.so \
         share/doc/molscope/README.md include/molscope/ms_plugin.h; do
    if [ -e "$prefix/$f" ]; then pass "installed $f"; else fail "installed $f" "missing"; fi
done
out=$(cd "$scratch" && env -u MOLSCOPE_TCLLIB -u MOLSCOPE_PLUGINDIR \
      "$prefix/bin/molscope" -dispdev text "$MS_TEST_DATA/1tii.pdb" 2>&1 <<'TCL'
puts "[molinfo top get numatoms] [file normalize $env(MOLSCOPE_TCLLIB)] [parallel nodecount]"
TCL
)
expect_eq "installed program loads a PDB with its own plugins, Tcl library and parallel package" \
    "$out" "5684 $(cd "$prefix/share/molscope/tcl" && pwd -P) 1"
# Moved elsewhere, it still finds them (relative to its own location).
mv "$prefix" "$scratch/moved"
out=$(cd "$scratch" && env -u MOLSCOPE_TCLLIB -u MOLSCOPE_PLUGINDIR \
      "$scratch/moved/bin/molscope" -dispdev text "$MS_TEST_DATA/pept.pdb" 2>&1 <<'TCL'
puts [molinfo top get numatoms]
TCL
)
expect_eq "a relocated install still works" "$out" "107"
rm -rf "$scratch"
