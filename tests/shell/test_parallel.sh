# test_parallel.sh: molscope and the molscope::parallel package under mpirun with 3 ranks:
# start-up, `parallel for` (every index exactly once), allreduce in rank order, allgather,
# barrier, errors on one rank ending the whole job within seconds, the package in a plain
# tclsh, rank 0's standard input reaching every rank, and broadcast loading (ranks 1 and 2
# run where the file does not exist, so they can only have it from rank 0).
. "$(dirname "$0")/lib.sh"
D=$MS_TEST_DATA
mpi_job_setup
if ! command -v mpirun >/dev/null; then skip "mpi" "no mpirun"; exit 0; fi
# mpi NP ARGS...: mpirun with a limit, so a hang fails instead of stopping the suite (its
# ranks write through a terminal: drop the carriage returns).
mpi() { local np=$1; shift; timeout 60 mpirun -np "$np" "$@" | tr -d '\r'; return "${PIPESTATUS[0]}"; }
# within T0 SECONDS: whether less than SECONDS passed since T0 (an $EPOCHREALTIME)
within() { awk -v a="$1" -v b="$EPOCHREALTIME" -v s="$2" 'BEGIN{print (b - a < s) ? 1 : 0}'; }

out=$(echo 'puts [parallel nodecount]' | mpi 2 $M 2>&1)
if [ "$(printf '%s\n' "$out" | grep -c '^2$')" != 2 ]; then
    skip "mpi" "molscope is built without MPI or mpirun does not start it: $(echo "$out" | tail -1)"
    exit 0
fi

# ---------------------------------------------------------------- the forms
cat > forms.tcl <<'TCL'
set r [parallel noderank]
proc work {i ud} { puts "I $::r $i $ud"; after 20 }
parallel for 1 20 work ud
puts "N $r [parallel nodecount]"
proc cat2 {a b} { return "$a$b" }
puts "C $r [parallel allreduce cat2 r$r]"
proc lin {a b} { expr {2 * $a + $b} }
puts "L $r [parallel allreduce lin [expr {$r + 1}]]"
puts "G $r [parallel allgather [list rank $r]]"
if {$r == 1} { after 700; close [open flag w] }
parallel barrier
puts "B $r [file exists flag]"
TCL
out=$(mpi 3 $M -e forms.tcl </dev/null 2>/dev/null); rc=$?
expect_eq "3 ranks run the script" "$rc" 0
idx=$(printf '%s\n' "$out" | awk '$1=="I"{print $3}' | sort -n | tr '\n' ' ')
expect_eq "parallel for 1 20: every index exactly once" "$idx" "$(seq 1 20 | tr '\n' ' ')"
expect_eq "parallel for: userdata reaches the proc" \
    "$(printf '%s\n' "$out" | awk '$1=="I"{print $4}' | sort -u)" "ud"
workers=$(printf '%s\n' "$out" | awk '$1=="I"{print $2}' | sort -u | wc -l)
expect_eq "parallel for: the indices are shared by all 3 ranks" "$workers" 3
expect_eq "noderank and nodecount" "$(printf '%s\n' "$out" | awk '$1=="N"{print $2, $3}' | sort | tr '\n' ,)" \
    "0 3,1 3,2 3,"
expect_eq "allreduce with concatenation: rank order, the same on every rank" \
    "$(printf '%s\n' "$out" | awk '$1=="C"{print $3}' | sort | uniq -c | awk '{print $1, $2}')" "3 r0r1r2"
# ((2*1 + 2) * 2 + 3) = 11 folding left to right; any other order gives another number
expect_eq "allreduce with a non-commutative proc folds left to right" \
    "$(printf '%s\n' "$out" | awk '$1=="L"{print $3}' | sort | uniq -c | awk '{print $1, $2}')" "3 11"
expect_eq "allgather: every rank's value in rank order" \
    "$(printf '%s\n' "$out" | grep '^G ' | cut -d' ' -f3- | sort | uniq -c | sed 's/^ *//')" \
    "3 {rank 0} {rank 1} {rank 2}"
expect_eq "barrier: no rank passes before rank 1 arrives" \
    "$(printf '%s\n' "$out" | awk '$1=="B"{print $3}' | sort | uniq -c | awk '{print $1, $2}')" "3 1"

# ---------------------------------------------------------------- errors end the job
echo 'if {[parallel noderank] == 1} { error "boom on rank 1" }; parallel barrier; puts never' > err.tcl
t0=$EPOCHREALTIME
out=$(mpi 3 $M -e err.tcl </dev/null 2>&1); rc=$?
fast=$(within "$t0" 10)
expect_match "an error on rank 1 only ends the job with a non-zero status" "$rc" "[1-9]*"
expect_eq "... within seconds (others were waiting in a barrier)" "$fast" 1
expect_match "... with rank 1's message" "$out" "*boom on rank 1*"
expect_eq "... and no rank went on" "$(printf '%s\n' "$out" | grep -c '^never')" 0
cat > forerr.tcl <<'TCL'
proc work {i ud} { after 10; if {$i == 9} { error "index nine failed" } }
parallel for 1 30 work {}
puts never
TCL
out=$(mpi 3 $M -e forerr.tcl </dev/null 2>&1); rc=$?
expect_match "an error in a parallel for callback ends the job" "$rc:$out" "[1-9]*index nine failed*"
expect_eq "... before anyone goes on" "$(printf '%s\n' "$out" | grep -c '^never')" 0
out=$(echo 'if {[parallel noderank] == 2} { quit 3 }; parallel barrier' | mpi 3 $M 2>&1); rc=$?
expect_match "quit with a non-zero status on one rank ends the job" "$rc" "[1-9]*"

# ---------------------------------------------------------------- standard input
out=$(printf 'set x [expr {6 * 7}]\nputs "S [parallel noderank] $x"\n' | mpi 3 $M 2>/dev/null)
expect_eq "rank 0's standard input runs on every rank" "$(printf '%s\n' "$out" | grep '^S' | sort | tr '\n' ,)" \
    "S 0 42,S 1 42,S 2 42,"
expect_eq "only rank 0 echoes results" "$(printf '%s\n' "$out" | grep -c '^42$')" 1

# ---------------------------------------------------------------- plain tclsh
if command -v tclsh >/dev/null; then
    cat > pkg.tcl <<'TCL'
lappend auto_path $env(MOLSCOPE_TCLLIB)
package require molscope::parallel
proc cat2 {a b} { return "$a$b" }
proc work {i ud} { puts "I $i" }
parallel for 1 10 work {}
puts "T [parallel noderank] [parallel nodecount] [parallel allreduce cat2 [parallel noderank]]"
if {[lindex $argv 0] eq "fail" && [parallel noderank] == 2} { error "tclsh rank 2 fails" }
parallel barrier
TCL
    out=$(mpi 3 tclsh pkg.tcl 2>/dev/null); rc=$?
    expect_eq "tclsh under mpirun: package require molscope::parallel" "$rc:$(printf '%s\n' "$out" | grep '^T' | sort | tr '\n' ,)" \
        "0:T 0 3 012,T 1 3 012,T 2 3 012,"
    expect_eq "tclsh: parallel for runs each index once" \
        "$(printf '%s\n' "$out" | awk '$1=="I"{print $2}' | sort -n | tr '\n' ' ')" "$(seq 1 10 | tr '\n' ' ')"
    out=$(mpi 3 tclsh pkg.tcl fail 2>&1); rc=$?
    expect_match "tclsh: a script error on rank 2 ends the job" "$rc:$out" "[1-9]*tclsh rank 2 fails*"
    out=$(tclsh pkg.tcl 2>&1)
    expect_eq "tclsh without mpirun: one rank" "$(printf '%s\n' "$out" | grep '^T')" "T 0 1 0"
else
    skip "tclsh" "no tclsh"
fi

# ---------------------------------------------------------------- without MPI
echo 'puts "[parallel nodecount] [parallel allgather x]"' > one.tcl
out=$(MOLSCOPE_NOMPI=1 mpi 2 -x MOLSCOPE_NOMPI $M -e one.tcl </dev/null 2>&1)
expect_eq "MOLSCOPE_NOMPI: every process is a job of one" "$(printf '%s\n' "$out" | sort | tr '\n' ,)" "1 x,1 x,"

# ---------------------------------------------------------------- broadcast loading
# Rank 0 runs in A, where x.pdb is; ranks 1 and 2 in B, where it is not.
mkdir -p A B; cp "$D/1tii.pdb" A/x.pdb
echo 'animate write pdb ../out[parallel noderank].pdb; puts "A [parallel noderank] [molinfo top get {numatoms numframes}]"' > w.tcl
mpmd() {
    timeout 60 mpirun -np 1 -wdir "$scratch/A" "$@" : -np 2 -wdir "$scratch/B" "$@" | tr -d '\r'
    return "${PIPESTATUS[0]}"
}
out=$(mpmd $M x.pdb -e "$scratch/w.tcl" </dev/null 2>&1); rc=$?
expect_eq "a command-line file is loaded by rank 0 and broadcast" \
    "$rc:$(printf '%s\n' "$out" | grep '^A' | sort | tr '\n' ,)" "0:A 0 5684 1,A 1 5684 1,A 2 5684 1,"
(cd A && echo 'animate write pdb ../ref.pdb' | $M x.pdb >/dev/null 2>&1)
sums=$(md5sum ref.pdb out0.pdb out1.pdb out2.pdb 2>/dev/null | awk '{print $1}' | sort -u | wc -l)
expect_eq "every rank's molecule equals a serial load (names, coordinates, all written out)" "$sums" 1
out=$(MOLSCOPE_NOBCAST=1 mpmd -x MOLSCOPE_NOBCAST $M x.pdb -e "$scratch/w.tcl" </dev/null 2>&1); rc=$?
expect_match "MOLSCOPE_NOBCAST: each rank reads for itself (and 1, 2 cannot)" "$rc:$out" "[1-9]*x.pdb: No such file*"

# Trajectory frames in a script: mol new + mol addfile with bcast on.
awk 'BEGIN{for(k=0;k<6;k++){printf "MODEL %d\n",k+1;
  printf "ATOM      1  N   ALA A   1    %8.3f   0.000   0.000  1.00  0.00           N\n",k;
  printf "ATOM      2  CA  ALA A   1    %8.3f   1.400   0.000  1.00  0.00           C\n",k*2;
  print "ENDMDL"}}' > A/models.pdb
sed '/^MODEL 4/,/^ENDMDL/s/   0.000   0.000  1.00/   0.0x0   0.000  1.00/' A/models.pdb > A/bad.pdb
cat > traj.tcl <<'TCL'
if {[catch {mol new bad.pdb bcast on} msg]} { puts "R [parallel noderank] $msg" }
mol new models.pdb bcast on
mol addfile models.pdb bcast on first 2
puts "F [parallel noderank] [molinfo top get {numatoms numframes frame}] [lindex [molinfo top get filename] 0]"
animate write pdb ../traj[parallel noderank].pdb beg 0 end -1
if {[catch {mol new missing.pdb bcast on} msg]} { puts "E [parallel noderank] $msg" }
if {[catch {mol new [lindex {models.pdb x.pdb x.pdb} [parallel noderank]] bcast on} msg]} {
    puts "D [parallel noderank] $msg"
}
proc cb {i ud} { if {[catch {mol new models.pdb bcast on} msg]} { puts "P $msg" } }
parallel for 0 0 cb {}
puts "M [parallel noderank] [molinfo num]"
TCL
out=$(mpmd $M -e "$scratch/traj.tcl" </dev/null 2>&1); rc=$?
expect_eq "mol new/addfile bcast on: frames of a trajectory reach every rank" \
    "$rc:$(printf '%s\n' "$out" | grep '^F' | sort | tr '\n' ,)" \
    "0:F 0 2 10 9 models.pdb models.pdb,F 1 2 10 9 models.pdb models.pdb,F 2 2 10 9 models.pdb models.pdb,"
sums=$(md5sum traj0.pdb traj1.pdb traj2.pdb | awk '{print $1}' | sort -u | wc -l)
expect_eq "... with the same coordinates in every frame" "$sums:$(grep -c '^ATOM' traj0.pdb)" "1:20"
expect_match "a bad frame in a broadcast trajectory fails the load on every rank alike" \
    "$(printf '%s\n' "$out" | grep '^R' | cut -d' ' -f3- | sort | uniq -c | sed 's/^ *//')" \
    "3 mol new: bad.pdb: frame 3: *bad y coordinate*"
expect_eq "a failed broadcast load is every rank's error, with rank 0's message" \
    "$(printf '%s\n' "$out" | grep '^E' | cut -d' ' -f3- | sort | uniq -c | sed 's/^ *//')" \
    "3 mol new: missing.pdb: No such file or directory"
expect_match "ranks loading different files together get an error, not a hang" \
    "$(printf '%s\n' "$out" | grep -c '^D .*do not all load')" 3
expect_match "bcast inside a parallel for callback is refused" \
    "$(printf '%s\n' "$out" | grep '^P')" "P mol new: bcast on cannot be used inside a parallel for*"
expect_eq "... and the failed loads left no molecule behind" \
    "$(printf '%s\n' "$out" | grep '^M' | awk '{print $3}' | sort -u)" 1

# A broadcast load on rank 0 alone: the others never come; the job ends, it does not hang.
echo 'if {[parallel noderank] == 0} { mol new x.pdb bcast on }; after 4000' > alone.tcl
t0=$EPOCHREALTIME
out=$(MOLSCOPE_BCAST_TIMEOUT=1 mpmd -x MOLSCOPE_BCAST_TIMEOUT $M -e "$scratch/alone.tcl" </dev/null 2>&1); rc=$?
fast=$(within "$t0" 15)
expect_match "bcast on rank 0 alone ends the job after the timeout" "$rc:$out" "[1-9]*is it run on rank 0 only*"
expect_eq "... within seconds" "$fast" 1
rm -rf "$scratch"
