# test_dist.sh: the release tarball (`make dist`) carries every file of the repository
# that the build, the tests and the documentation use, so that `make distcheck` (which
# builds the tarball out of tree and runs the tests) finds nothing missing. Files that only
# serve the repository (.ci/, .gitignore) are left out on purpose.
. "$(dirname "$0")/lib.sh"
if ! command -v git > /dev/null || ! git -C "$MS_SRCDIR" rev-parse HEAD > /dev/null 2>&1; then
    skip "make dist carries every committed file" "not a git checkout"
    rm -rf "$scratch"; exit 0
fi
if ! make -s -C "$MS_BUILDDIR" distdir distdir="$scratch/d" > "$scratch/dist.log" 2>&1; then
    fail "make distdir" "$(tail -3 "$scratch/dist.log")"
    rm -rf "$scratch"; exit 0
fi
pass "make distdir"
missing=$(cd "$MS_SRCDIR" && git ls-files | grep -vE '^(\.ci/|\.gitignore$)' |
          while read -r f; do [ -e "$scratch/d/$f" ] || echo "$f"; done | head -10 | tr '\n' ' ')
expect_eq "every committed file is in the tarball" "$missing" ""
for f in configure Makefile.in doc/molscope.1 tcl/init.tcl tests/fresh-install scripts/gpu-check; do
    if [ -e "$scratch/d/$f" ]; then pass "the tarball has $f"; else fail "the tarball has $f" "missing"; fi
done
chmod -R u+w "$scratch"; rm -rf "$scratch"
