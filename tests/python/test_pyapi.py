"""test_pyapi.py: runs the pytest suite of molscope's Python API (tests/pyapi: the molscope
package against the Tcl commands it wraps, vmdnumpy, Python inside the molscope program)
under Debian's python3 and reports each pytest test as a PASS/FAIL/SKIP line. Skipped as a
whole when molscope was configured without Python (no src/python/_molscope.so) or when
python3-pytest is missing."""
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mstest import Reporter  # noqa: E402

SRCDIR = os.environ.get("MS_SRCDIR") or os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
BUILDDIR = os.environ.get("MS_BUILDDIR", SRCDIR)
R = Reporter("pyapi")

KINDS = ("PASSED", "FAILED", "ERROR", "SKIPPED", "XFAIL", "XPASS")


def parse(line):
    """(kind, test name, why) of a line of pytest's -rA summary, or None. The lines are
    `PASSED file::test`, `FAILED file::test - why` and `SKIPPED [n] file:line: why`."""
    kind, _, rest = line.partition(" ")
    if kind not in KINDS:
        return None
    if kind == "SKIPPED":
        m = re.match(r"\[\d+\] (\S+?:\d+): (.*)", rest)
        return (kind, m.group(1), m.group(2)) if m else (kind, rest, "")
    node, _, why = rest.partition(" - ")
    return kind, node.split("::", 1)[-1], why


def main():
    if not os.path.exists(os.path.join(BUILDDIR, "src", "python", "_molscope.so")):
        R.skip("all", "molscope was configured without Python (--without-python or no libpython3-dev)")
        return 0
    try:
        import pytest  # noqa: F401
    except ImportError:
        R.skip("all", "python3-pytest is not installed (scripts/bootstrap --test)")
        return 0
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1",
               PYTHONPATH=os.pathsep.join([os.path.join(BUILDDIR, "src", "python"),
                                           os.path.join(SRCDIR, "tests", "pyapi")]))
    p = subprocess.run([sys.executable, "-m", "pytest", "-rA", "-q", "-p", "no:cacheprovider",
                        os.path.join(SRCDIR, "tests", "pyapi")],
                       capture_output=True, text=True, env=env, cwd=BUILDDIR)
    seen = 0
    for line in p.stdout.splitlines():
        r = parse(line)
        if not r:
            continue
        seen += 1
        kind, name, why = r
        if kind in ("PASSED", "XFAIL"):
            R.report(True, name)
        elif kind == "SKIPPED":
            R.skip(name, why)
        else:
            R.report(False, name, why or kind)
    if p.returncode not in (0, 1) or (p.returncode == 1 and not R.failures) or not seen:
        R.report(False, "pytest run", "status %d: %s" % (p.returncode, (p.stdout + p.stderr)[-2000:]))
    return 1 if R.failures else 0


if __name__ == "__main__":
    sys.exit(main())
