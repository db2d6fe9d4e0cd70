# test_cli.sh: molscope's command line, startup order, batch and interactive shells.
. "$(dirname "$0")/lib.sh"
D=$MS_TEST_DATA
cd "$scratch"
export HOME="$scratch/home"; mkdir -p "$HOME"

out=$($MOLSCOPE -h); rc=$?
expect_eq "-h exits 0" "$rc" 0
expect_match "-h shows usage" "$out" "usage: *-dispdev*-args*"
out=$($MOLSCOPE --version)
expect_match "--version" "$out" "molscope [0-9]*"

out=$($MOLSCOPE -frobnicate 2>&1 </dev/null); rc=$?
expect_eq "unknown option exits 2" "$rc" 2
expect_match "unknown option named" "$out" "*unknown option -frobnicate*"
out=$($MOLSCOPE -size 0 10 2>&1 </dev/null); rc=$?
expect_match "bad -size rejected" "$rc:$out" "2:*-size: bad width '0'*"

out=$(echo 'puts "[llength $argv] $argc [lindex $argv 1] [file tail $argv0]"' |
      $MOLSCOPE -dispdev text -args a "b c" d)
expect_eq "-args: argv argc argv0" "$out" "3 3 b c molscope"

out=$(echo 'puts ok; error boom; puts never' | $MOLSCOPE -dispdev text 2>&1); rc=$?
expect_eq "batch error exits 1" "$rc" 1
expect_match "batch error prints message and stack" "$out" "ok*boom*while executing*error boom*"
out=$(printf 'puts [expr {1+\n2}]\n' | $MOLSCOPE -dispdev text 2>&1)
expect_eq "commands may span lines" "$out" "3"
out=$(echo 'quit 3; puts never' | $MOLSCOPE -dispdev text 2>&1); rc=$?
expect_eq "quit status" "$rc:$out" "3:"
out=$(printf 'proc f {} {exit 4}\nf\nputs never\n' | $MOLSCOPE -dispdev text 2>&1); rc=$?
expect_eq "exit from a proc ends the program" "$rc:$out" "4:"
echo 'puts "script [molinfo num]"; error "in script"' > err.tcl
out=$($MOLSCOPE -dispdev text -e err.tcl </dev/null 2>&1); rc=$?
expect_match "-e script error exits 1 with the file named" "$rc:$out" "1:*err.tcl*in script*"
echo 'puts done' > q.tcl
out=$($MOLSCOPE -dispdev text -e q.tcl </dev/null 2>&1); rc=$?
expect_eq "batch ends at EOF with status 0" "$rc:$out" "0:done"

# Startup order: init.tcl, then files, then the rc file, then -e
echo 'puts "rc [molinfo num] [info exists ::molscope::libdir]"' > .molscoperc
echo 'puts "e [molinfo num]"; quit' > e.tcl
out=$($MOLSCOPE -dispdev text $D/pept.pdb -e e.tcl </dev/null 2>&1)
expect_eq "order: init, files, .molscoperc, -e" "$out" "$(printf 'rc 1 1\ne 1')"
echo 'puts "home rc"' > "$HOME/.molscoperc"
out=$($MOLSCOPE -dispdev text -e e.tcl </dev/null 2>&1)
expect_eq "./.molscoperc wins over ~/.molscoperc" "$(echo "$out" | head -1)" "rc 0 1"
rm .molscoperc
out=$($MOLSCOPE -dispdev text -e e.tcl </dev/null 2>&1)
expect_eq "~/.molscoperc when there is none here" "$(echo "$out" | head -1)" "home rc"
rm "$HOME/.molscoperc"; echo 'puts "vmdrc"' > .vmdrc
out=$($MOLSCOPE -dispdev text -e e.tcl </dev/null 2>&1)
expect_eq "a user's .vmdrc when there is no .molscoperc" "$(echo "$out" | head -1)" "vmdrc"
echo 'puts "custom"' > custom.tcl
out=$($MOLSCOPE -dispdev text -startup custom.tcl -e e.tcl </dev/null 2>&1)
expect_eq "-startup replaces the rc files" "$(echo "$out" | head -1)" "custom"
rm .vmdrc

# Files on the command line: -f (one molecule) and -m (one each); -<type>
out=$(echo 'puts "[molinfo num] [molinfo top get numframes]"' | $MOLSCOPE -dispdev text $D/pept.pdb $D/pept.pdb)
expect_eq "-f: later files add frames to one molecule" "$out" "1 2"
out=$(echo 'puts "[molinfo num]"' | $MOLSCOPE -dispdev text -m $D/pept.pdb $D/tiny.pdb)
expect_eq "-m: each file a molecule" "$out" "2"
cp $D/pept.pdb pept.data
out=$(echo 'puts "[molinfo top get {numatoms filetype}]"' | $MOLSCOPE -dispdev text -pdb pept.data)
expect_eq "-pdb forces the type" "$out" "107 pdb"
out=$($MOLSCOPE -dispdev text nonexistent.pdb </dev/null 2>&1); rc=$?
expect_match "a missing command-line file fails the batch run" "$rc:$out" "1:*nonexistent.pdb*No such file*"
out=$(echo 'puts [molinfo num]' | $MOLSCOPE -dispdev cave 2>&1)
expect_match "unbuilt display device reported, text used" "$out" "*'cave' is not built*0"

# Interactive: a terminal on stdin gives a prompt and keeps going after errors.
if /usr/bin/python3 -c 'import pty' 2>/dev/null; then
    out=$(/usr/bin/python3 - "$MOLSCOPE" <<'PY'
import os, pty, sys, time, select
pid, fd = pty.fork()
if pid == 0:
    os.environ["MOLSCOPE_NOREADLINE"] = "1"
    os.execv(sys.argv[1], [sys.argv[1], "-dispdev", "text"])
buf = b""
def drain(t=1.5):
    global buf
    end = time.time() + t
    while time.time() < end:
        r, _, _ = select.select([fd], [], [], 0.1)
        if r:
            try: buf += os.read(fd, 4096)
            except OSError: return
drain()
os.write(fd, b"expr {6*7}\n"); drain()
os.write(fd, b"error oops\n"); drain()
os.write(fd, b"set x 5\n"); drain()
os.write(fd, b"\x04"); drain()
_, status = os.waitpid(pid, 0)
text = buf.decode(errors="replace").replace("\r", "")
print("prompt" if "molscope > " in text else "noprompt",
      "42" if "\n42\n" in text or "> 42\n" in text else "no42",
      "oops" if "oops" in text else "nooops",
      "after" if "\n5\n" in text or "> 5\n" in text else "noafter",
      "exit%d" % os.WEXITSTATUS(status))
PY
)
    expect_eq "interactive: prompt, results, errors do not end it, EOF exits 0" "$out" "prompt 42 oops after exit0"
else
    skip "interactive" "python3 pty not available"
fi
rm -rf "$scratch"
