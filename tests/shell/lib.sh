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
# mpi_job_setup: the start of the tests that run molscope under mpirun: into $scratch with
# its own HOME, Open MPI allowed as root and to oversubscribe, M the text-mode molscope.
mpi_job_setup() {
    cd "$scratch"
    export HOME="$scratch/home"; mkdir -p "$HOME"
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    export OMPI_MCA_rmaps_base_oversubscribe=1
    M="$MOLSCOPE -dispdev text"
}
