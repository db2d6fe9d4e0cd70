# test_background.sh: background frame loading (waitfor 1) in every input mode: `update`,
# `display update` and `vwait` deliver every pending frame and never hang on standard
# input; a file found damaged while its frames are read in the background is reported at
# once (stderr, or the script's bgerror) naming the file, the frame and the problem, and the
# frames before the damage stay.
. "$(dirname "$0")/lib.sh"
D=$MS_TEST_DATA
cd "$scratch"
export HOME="$scratch/home"; mkdir -p "$HOME"
T="timeout 20"
# A copy of helix.dcd (10 frames) cut 940 bytes into frame 6.
head -c 30000 "$D/helix.dcd" > cut.dcd

# `update` with standard input at its end (the shell used to spin on it for ever).
out=$(echo update | $T $MOLSCOPE -dispdev text 2>&1); rc=$?
expect_eq "echo update | molscope ends" "$rc:$out" "0:"
out=$(echo 'update; quit 3' | $T $MOLSCOPE -dispdev text 2>&1); rc=$?
expect_eq "update; quit 3 ends with status 3" "$rc:$out" "3:"
out=$(printf 'update\nputs a\nupdate idletasks\nputs b\n' | $T $MOLSCOPE -dispdev text 2>&1); rc=$?
expect_eq "the lines after update are read, in order" "$rc:$out" "$(printf '0:a\nb')"
out=$(printf 'proc p {} {update; puts in-p}\np\nputs after\n' | $T $MOLSCOPE -dispdev text 2>&1)
expect_eq "no line is evaluated inside update" "$out" "$(printf 'in-p\nafter')"
out=$(printf 'after 100 {set v 1}; vwait v\nputs v=$v\n' | $T $MOLSCOPE -dispdev text 2>&1)
expect_eq "vwait on an after from standard input" "$out" "v=1"

# Each way of waiting, after a load with the default waitfor 1, has every frame.
load="mol new $D/helix.psf; mol addfile $D/helix.dcd"
report='puts "n=[molinfo top get numframes] t=$vmd_trajectory_read(0)"'
waits=("update" "update idletasks" "display update" "after 0 {set v 1}; vwait v"
       "after 50 {set v 1}; vwait v")
for w in "${waits[@]}"; do
    printf '%s\n%s\n%s\n' "$load" "$w" "$report" > s.tcl
    out=$($T $MOLSCOPE -dispdev text < s.tcl 2>&1 | grep '^n='); rc=$?
    expect_eq "stdin: '$w' delivers every frame" "$out" "n=10 t=$D/helix.dcd"
    out=$($T $MOLSCOPE -dispdev text -e s.tcl < /dev/null 2>&1 | grep -v '^0$')
    expect_eq "-e: '$w' delivers every frame" "$out" "n=10 t=$D/helix.dcd"
    out=$($T $MOLSCOPE -dispdev text -eofexit < s.tcl 2>&1 | grep '^n=')
    expect_eq "-eofexit: '$w' delivers every frame" "$out" "n=10 t=$D/helix.dcd"
done
# -e script, then commands from standard input
printf '%s\n' "$load" > e.tcl
out=$(printf 'update\n%s\n' "$report" | $T $MOLSCOPE -dispdev text -e e.tcl 2>&1 | grep '^n=')
expect_eq "-e load, update from standard input" "$out" "n=10 t=$D/helix.dcd"
# Frames arrive without any wait while the shell idles between lines.
out=$( (printf '%s\n' "$load"; sleep 1; printf '%s\n' "$report") |
       $T $MOLSCOPE -dispdev text 2>&1 | grep '^n=')
expect_eq "frames arrive while the shell waits for input" "$out" "n=10 t=$D/helix.dcd"

# A terminal on standard input (with and without tclreadline).
if /usr/bin/python3 -c 'import pty' 2>/dev/null; then
    for rl in 0 1; do
        out=$(/usr/bin/python3 - "$MOLSCOPE" "$D" "$rl" <<'PY'
import os, pty, select, sys, time
exe, data, readline = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
pid, fd = pty.fork()
if pid == 0:
    if readline:
        os.environ.pop("MOLSCOPE_NOREADLINE", None)
    else:
        os.environ["MOLSCOPE_NOREADLINE"] = "1"
    os.execv(exe, [exe, "-dispdev", "text"])
buf = b""
def drain(t):
    global buf
    end = time.time() + t
    while time.time() < end:
        r, _, _ = select.select([fd], [], [], 0.05)
        if r:
            try:
                buf += os.read(fd, 4096)
            except OSError:
                return
drain(1.0)
for w in ["update", "display update", "after 0 {set ::v 1}; vwait ::v"]:
    for c in ["mol new %s/helix.psf" % data, "mol addfile %s/helix.dcd" % data, w,
              'puts "n=[molinfo top get numframes]"', "mol delete all"]:
        os.write(fd, c.encode() + b"\n")
        drain(0.3)
os.write(fd, b"quit\n")
drain(1.0)
_, status = os.waitpid(pid, 0)
lines = buf.decode(errors="replace").replace("\r", "").split("\n")
print(" ".join(l for l in lines if l.startswith("n=")), "exit%d" % os.WEXITSTATUS(status))
PY
)
        expect_eq "terminal (readline $rl): update, display update, vwait" "$out" "n=10 n=10 n=10 exit0"
    done
else
    skip "terminal" "python3 pty not available"
fi

# (A -e script echoes each command's result as VMD does: the molecule ids are left out.)
# A file damaged in the background: the message names the file, the frame and the problem;
# the 6 frames before the damage stay.
msg="molecule 0: $scratch/cut.dcd: frame 6: truncated: *; the 6 frames read before it are kept*"
printf 'mol new %s/helix.psf\nmol addfile %s/cut.dcd\nupdate\n%s\n' "$D" "$scratch" \
    'puts "n=[molinfo top get numframes]"' > cut.tcl
out=$($T $MOLSCOPE -dispdev text < cut.tcl 2>err.txt | grep '^n='); rc=$?
expect_eq "stdin: a damaged file keeps the frames before the damage" "$out" "n=6"
expect_match "stdin: the damage is reported on stderr" "$(cat err.txt)" "$msg"
out=$($T $MOLSCOPE -dispdev text -e cut.tcl < /dev/null 2>err.txt | grep -v '^0$'); rc=$?
expect_eq "-e: a damaged file keeps the frames before the damage" "$rc:$out" "0:n=6"
expect_match "-e: the damage is reported on stderr" "$(cat err.txt)" "$msg"
expect_eq "-e: reported once" "$(grep -c 'frame 6: truncated' err.txt)" "1"
# ... at the moment it is found: before the next command's output, through bgerror
printf '%s\n%s\n%s\n%s\n' 'proc bgerror {m} {puts "bgerror: $m ($::errorCode)"}' \
    "mol new $D/helix.psf" "mol addfile $scratch/cut.dcd; display update" \
    'puts "n=[molinfo top get numframes]"' > bg.tcl
out=$($T $MOLSCOPE -dispdev text < bg.tcl 2>&1 | grep -v '^0$')
expect_match "stdin: bgerror gets it before the next command" "$out" \
    "bgerror: $msg (MOLSCOPE LOAD 0 $scratch/cut.dcd)
n=6"
out=$($T $MOLSCOPE -dispdev text -e bg.tcl < /dev/null 2>&1 | grep -v '^0$')
expect_match "-e: bgerror gets it before the next command" "$out" "bgerror: $msg*
n=6"
# Without any wait: found at idle time while the shell waits for input.
out=$( (printf 'mol new %s/helix.psf\nmol addfile %s/cut.dcd\n' "$D" "$scratch"; sleep 1;
        echo 'puts "n=[molinfo top get numframes]"') | $T $MOLSCOPE -dispdev text 2>&1 | grep -v '^0$')
expect_match "stdin: found while idle, reported before the next line runs" "$out" "$msg
n=6"
# A later file on the same molecule: the earlier file's damage is its own, then the new
# file's frames follow.
printf 'mol new %s/helix.psf\nmol addfile %s/cut.dcd\nmol addfile %s/helix.dcd waitfor all\n%s\n' \
    "$D" "$scratch" "$D" 'puts "n=[molinfo top get numframes]"' > two.tcl
out=$($T $MOLSCOPE -dispdev text < two.tcl 2>err.txt | grep '^n=')
expect_eq "a damaged earlier file does not stop the next one" "$out" "n=16"
expect_match "the damage names the earlier file" "$(cat err.txt)" "$msg"
rm -rf "$scratch"
