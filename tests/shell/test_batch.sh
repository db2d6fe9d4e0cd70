# test_batch.sh: scripts read as VMD reads them (-e, the startup file, standard input): one
# complete command at a time, a failing command printed and the next one run; at the end a
# line on stderr says how many failed and which was first, and the exit status is 1 (the
# one difference from VMD, which exits 0) unless quit gave another.
. "$(dirname "$0")/lib.sh"
D=$MS_TEST_DATA
cd "$scratch"
export HOME="$scratch/home"; mkdir -p "$HOME"
M="$MOLSCOPE -dispdev text"

printf 'puts one\nnosuchcommand 1 2\nputs [expr {2 +\n 3}]\nerror "second failure"\nputs last\n' > e.tcl
out=$($M -e e.tcl </dev/null 2>err.txt); rc=$?
expect_eq "-e: every command after a failure runs" "$out" "$(printf 'one\ninvalid command name "nosuchcommand"\n5\nsecond failure\nlast')"
expect_eq "-e: status 1 when a command failed" "$rc" 1
expect_eq "-e: the summary is the last line on stderr" "$(tail -1 err.txt)" \
    "molscope: 2 commands failed; the first: e.tcl line 2: invalid command name \"nosuchcommand\""
expect_match "-e: each failure named with its file and line, with its stack trace" "$(cat err.txt)" \
    "molscope: e.tcl line 2: invalid command name*while executing*molscope: e.tcl line 5: second failure*"

out=$($M < e.tcl 2>err.txt); rc=$?
expect_eq "stdin: every command after a failure runs" "$(printf '%s\n' "$out" | tr '\n' ' ')" \
    'one invalid command name "nosuchcommand" 5 second failure last '
expect_eq "stdin: status 1 and the summary" "$rc:$(tail -1 err.txt)" \
    "1:molscope: 2 commands failed; the first: standard input line 2: invalid command name \"nosuchcommand\""

printf 'puts fine\nset x 1\n' > ok.tcl
out=$($M -e ok.tcl </dev/null 2>err.txt); rc=$?
expect_eq "no failure: status 0, nothing on stderr, results echoed" "$rc:$out:$(cat err.txt)" "0:$(printf 'fine\n1'):"

printf 'error early\nquit 3\n' > q.tcl
$M -e q.tcl </dev/null >/dev/null 2>err.txt; rc=$?
expect_eq "quit's own status wins" "$rc:$(tail -1 err.txt)" "3:molscope: 1 command failed; the first: q.tcl line 1: early"
printf 'error early\nquit\n' > q0.tcl
$M -e q0.tcl </dev/null >/dev/null 2>/dev/null; rc=$?
expect_eq "quit without a status after a failure: 1" "$rc" 1

printf 'puts before\nproc p {} {\n  puts never\n' > open.tcl
out=$($M -e open.tcl </dev/null 2>err.txt); rc=$?
expect_eq "a file ending inside an unfinished command fails" "$rc:$out:$(tail -1 err.txt)" \
    "1:$(printf 'before\nthe file ends inside an unfinished command (missing close-brace or quote)'):molscope: 1 command failed; the first: open.tcl line 2: the file ends inside an unfinished command (missing close-brace or quote)"
out=$(printf 'puts a\nset y {\n' | $M 2>err.txt); rc=$?
expect_eq "standard input ending inside a command fails" "$rc:$(tail -1 err.txt)" \
    "1:molscope: 1 command failed; the first: standard input line 2: standard input ended inside an unfinished command"

echo 'error "in the rc file"' > .molscoperc
printf 'puts "e ran"\n' > e2.tcl
out=$($M -e e2.tcl </dev/null 2>err.txt); rc=$?
expect_eq "a failing startup file: the -e script still runs, status 1" "$rc:$out" "1:$(printf 'in the rc file\ne ran')"
rm .molscoperc
out=$($M nonexistent.pdb -e e2.tcl </dev/null 2>err.txt); rc=$?
expect_match "a missing command-line file: counted, the -e script runs" "$rc:$out:$(tail -1 err.txt)" \
    "1:*e ran:molscope: 1 command failed; the first: command line: mol new: nonexistent.pdb*"

printf 'source s.tcl\nputs after\n' > src.tcl
printf 'puts s1\nerror "stops source"\nputs s2\n' > s.tcl
out=$($M -e src.tcl </dev/null 2>/dev/null); rc=$?
expect_eq "source stops at its first error; the outer file goes on" "$rc:$out" "1:$(printf 's1\nstops source\nafter')"
rm -rf "$scratch"
