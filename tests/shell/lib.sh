# lib.sh: helpers for shell-level tests: check NAME CMD... runs a check and prints
# PASS/FAIL lines the runner counts.
t_name=$(basename "$0" .sh)
pass() { echo "PASS: $t_name: $1"; }
fail() { echo "FAIL: $t_name: $1: $2"; }
skip() { echo "SKIP: $t_name: $1: $2"; }
# expect_eq NAME ACTUAL EXPECTED
expect_eq() { if [ "$2" = "$3" ]; then pass "$1"; else fail "$1" "got [$2], expected [$3]"; fi; }
# expect_match NAME ACTUAL GLOB
expect_match() { case "$2" in $3) pass "$1";; *) fail "$1" "got [$2], expected to match [$3]";; esac; }
MOLSCOPE=${MOLSCOPE:-molscope}
scratch=$(mktemp -d "${MS_TEST_OUT:-/tmp}/sh.XXXXXX")
