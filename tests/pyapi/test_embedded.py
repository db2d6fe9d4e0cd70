"""test_embedded.py: Python inside the molscope program: gopython -command, gopython
file.py, the interactive prompt (on a terminal, back to Tcl at its end), `-python -e`,
Python errors as Tcl errors carrying the traceback, SystemExit as quit, VMD's module names;
and a VMD-style script giving the same output under `molscope -python -e` and, with only
its import changed, under a plain python3."""
import os
import pty
import select
import subprocess
import sys
import time

import pytest

from conftest import SRCDIR, DATA

EXE = os.environ.get("MOLSCOPE") or os.path.join(SRCDIR, "src", "molscope")
HERE = os.path.dirname(os.path.abspath(__file__))


def molscope(args, stdin=subprocess.DEVNULL):
    env = dict(os.environ, MS_TEST_DATA=DATA)
    return subprocess.run([EXE, "-dispdev", "text"] + args, capture_output=True, text=True,
                          stdin=stdin, env=env, timeout=120)


def tcl_script(tmp_path, text):
    p = tmp_path / "script.tcl"
    p.write_text(text)
    return molscope(["-e", str(p)])


def test_gopython_command_shares_molecules(tmp_path):
    r = tcl_script(tmp_path, """
mol new %s/tiny.pdb
gopython -command "from vmd import molecule; print('py sees', molecule.listall(), molecule.numatoms(0))"
gopython -command "import molecule as m; m.new('made in python')"
puts "tcl sees [molinfo list] [molinfo 1 get name]"
gopython -command "print('top-level', atomsel('all', 0).molid, vmd.molecule is molecule)"
""" % DATA)
    assert r.returncode == 0, r.stderr
    n = int(r.stdout.split("py sees [0] ")[1].split()[0])
    assert n > 0
    assert "tcl sees 0 1 {made in python}" in r.stdout
    assert "top-level 0 True" in r.stdout


def test_gopython_file_and_errors(tmp_path):
    py = tmp_path / "f.py"
    py.write_text("x = 6 * 7\nprint('file ran', x, __file__.endswith('f.py'))\n")
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    return 1 / 0\nf()\n")
    r = tcl_script(tmp_path, """
gopython %s
gopython -command "print('x is still', x)"
if {[catch {gopython %s} msg]} { puts "CAUGHT<<$msg>>ENDCAUGHT" }
if {[catch {gopython -command "evaltcl('error {from tcl}')"} msg]} { puts "TCLERR<$msg>" }
if {[catch {gopython -command} msg]} { puts "USAGE<$msg>" }
if {[catch {gopython a b} msg]} { puts "USAGE2<$msg>" }
if {[catch {gopython /nonexistent.py} msg]} { puts "OPEN<$msg>" }
puts "still here"
""" % (py, bad))
    assert "file ran 42 True" in r.stdout and "x is still 42" in r.stdout
    caught = r.stdout.split("CAUGHT<<")[1].split(">>ENDCAUGHT")[0]
    assert caught.startswith("Traceback (most recent call last):")
    assert "bad.py\", line 2, in f" in caught and "ZeroDivisionError: division by zero" in caught
    assert "molscope.TclError: from tcl" in r.stdout
    assert "USAGE<gopython: wrong # args: usage: gopython ?<file.py>? | gopython -command <code>>" \
        in r.stdout
    assert "USAGE2<gopython: wrong # args" in r.stdout
    assert "OPEN<gopython: cannot open '/nonexistent.py'" in r.stdout
    assert "still here" in r.stdout
    assert r.returncode == 0


def test_uncaught_python_error_fails_the_command(tmp_path):
    r = tcl_script(tmp_path, 'gopython -command "raise KeyError(\'nope\')"\nputs next\n')
    assert "KeyError: 'nope'" in r.stdout and "next" in r.stdout
    assert r.returncode == 1 and "1 command failed" in r.stderr


def test_sys_exit_is_quit(tmp_path):
    r = tcl_script(tmp_path, 'gopython -command "import sys; sys.exit(3)"\nputs never\n')
    assert r.returncode == 3 and "never" not in r.stdout


def test_python_e_script(tmp_path):
    py = tmp_path / "s.py"
    py.write_text("from vmd import molecule\nprint('n', len(molecule.listall()))\n"
                  "evaltcl('puts from-tcl')\n")
    r = molscope(["%s/tiny.pdb" % DATA, "-python", "-e", str(py)])
    assert r.returncode == 0, r.stderr
    assert "n 1" in r.stdout and "from-tcl" in r.stdout
    bad = tmp_path / "bad.py"
    bad.write_text("import nosuchmodule_xyz\n")
    r = molscope(["-python", "-e", str(bad)])
    assert r.returncode == 1 and "ModuleNotFoundError" in r.stdout + r.stderr


def test_interactive_prompt_returns_to_tcl():
    pid, fd = pty.fork()
    if pid == 0:
        os.environ["MOLSCOPE_NOREADLINE"] = "1"
        os.execv(EXE, [EXE, "-dispdev", "text"])
    out = b""

    def read_until(token, limit=30):
        nonlocal out
        end = time.time() + limit
        while token not in out and time.time() < end:
            r, _, _ = select.select([fd], [], [], 0.5)
            if r:
                try:
                    out += os.read(fd, 4096)
                except OSError:
                    break
        return token in out

    os.write(fd, b"gopython\n")
    assert read_until(b">>> "), out
    os.write(fd, b"print(6 * 7)\n")
    assert read_until(b"42"), out
    os.write(fd, b"\x04")                  # end of input: back to Tcl
    os.write(fd, b"puts back-in-tcl[expr 1+1]\n")
    assert read_until(b"back-in-tcl2"), out
    os.write(fd, b"quit\n")
    read_until(b"never", 5)
    os.waitpid(pid, 0)
    os.close(fd)


def test_gopython_prompt_reads_piped_input():
    r = subprocess.run(
        [EXE, "-dispdev", "text"], input="puts before\ngopython\nx = 6 * 7\n"
        "for i in range(2):\n    print('loop', i)\n\nprint('x', x)\n",
        capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert "before" in r.stdout and "loop 1" in r.stdout and "x 42" in r.stdout


def test_vmd_style_script_same_under_molscope_and_python3(tmp_path):
    script = os.path.join(HERE, "vmd_style.py")
    r = molscope(["-python", "-e", script])
    assert r.returncode == 0, r.stderr
    text = open(script).read()
    changed = tmp_path / "molscope_style.py"
    changed.write_text(text.replace("from vmd import", "from molscope import", 1))
    env = dict(os.environ, MS_TEST_DATA=DATA)
    p = subprocess.run([sys.executable, str(changed)], capture_output=True, text=True,
                       env=env, timeout=120)
    assert p.returncode == 0, p.stderr
    lines = [l for l in r.stdout.splitlines() if l.strip()]
    assert lines == [l for l in p.stdout.splitlines() if l.strip()]
    assert lines[0] == "molecule 0: 392 atoms, 10 frames"
    assert lines[1].startswith("frame 0 before 0.000 rmsd 0.000")
    assert len(lines) == 15 and lines[-1] == "left []"
    assert float(lines[5].split()[3]) > 1.0     # frame 4 before the fit


def test_new_modules_under_vmd_names(tmp_path):
    """measure, topology, selection and axes import as VMD's names inside molscope, and
    render there is both VMD's module and molscope.render."""
    r = tcl_script(tmp_path, """
mol new %s/tiny.pdb
gopython -command "from vmd import measure, topology, selection, axes; import measure as m2; print('same', measure is m2, axes is vmd.axes)"
gopython -command "print('bond %%.3f' %% measure.bond(0, 1, 0)\\[0\\])"
gopython -command "img = render(size=(20, 10)); print('image', img.width, img.height, render.listall()\\[0\\])"
puts "tcl bond [format %%.3f [measure bond {0 1} molid 0]]"
""" % DATA)
    assert r.returncode == 0, r.stderr
    assert "same True True" in r.stdout and "image 20 10 snapshot" in r.stdout
    py = r.stdout.split("bond ")[1].split()[0]
    assert "tcl bond " + py in r.stdout
