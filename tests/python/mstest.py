"""mstest.py: what the cross-check scripts share: PASS/FAIL/SKIP lines as tests/run-tests
counts them, the start of their main() (the optional modules, the directories
tests/run-tests names, tests/tools/msdump built) and the output of tests/tools/msdump (the
molecule as molscope loads it)."""
import importlib
import os
import subprocess
import warnings


class Reporter:
    """Prints one line per check and counts the failures."""

    def __init__(self, suite):
        self.suite = suite
        self.failures = 0

    def report(self, ok, name, detail=""):
        if ok:
            print("PASS: %s: %s" % (self.suite, name))
        else:
            self.failures += 1
            print("FAIL: %s: %s: %s" % (self.suite, name, detail))

    def skip(self, name, why):
        print("SKIP: %s: %s: %s" % (self.suite, name, why))

    def steps(self, steps):
        """Run each callable in turn, a RuntimeError or a failed subprocess a failed check
        ("a step failed") before the next; returns the exit status (1 when any check
        failed)."""
        for step in steps:
            try:
                step()
            except (RuntimeError, subprocess.CalledProcessError) as e:
                self.report(False, "a step failed", str(e))
        return 1 if self.failures else 0

    def imports(self, names, package):
        """Import the modules named (warnings silenced first) and return them in order, or
        print the suite's SKIP line (package: what to install) and return None."""
        try:
            warnings.simplefilter("ignore")
            return [importlib.import_module(n) for n in names]
        except ImportError:
            print("SKIP: %s: %s is not installed" % (self.suite, package))
            return None

    def msdump_exe(self, builddir):
        """The path of tests/tools/msdump in builddir, or None after the suite's FAIL line
        when it is not built."""
        exe = os.path.join(builddir, "tests", "tools", "msdump")
        if not os.access(exe, os.X_OK):
            print("FAIL: %s: %s is not built (make check-build)" % (self.suite, exe))
            return None
        return exe


def dirs():
    """srcdir, builddir, the test data and the output directory, as tests/run-tests names
    them (MS_SRCDIR, MS_BUILDDIR, MS_TEST_DATA, MS_TEST_OUT); without it this source tree,
    built in place, and /tmp."""
    srcdir = os.environ.get("MS_SRCDIR", os.path.join(os.path.dirname(__file__), "..", ".."))
    builddir = os.environ.get("MS_BUILDDIR", srcdir)
    data = os.environ.get("MS_TEST_DATA", os.path.join(srcdir, "tests", "data"))
    outdir = os.environ.get("MS_TEST_OUT", "/tmp")
    return srcdir, builddir, data, outdir


def msdump(exe, files):
    """Load files the way `mol new`/`mol addfile` do and return what molscope read:
    natoms, nframes, atoms (name, resname, resid, segname, chain), per-frame cells and
    coordinates, and volumes (the numbers msdump prints for each)."""
    out = subprocess.run([exe] + files, capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(out.stderr.strip())
    d = {"atoms": [], "cells": [], "xyz": [], "volumes": []}
    for line in out.stdout.splitlines():
        f = line.split("\t")
        if f[0] == "natoms":
            d["natoms"] = int(f[1])
        elif f[0] == "nframes":
            d["nframes"] = int(f[1])
        elif f[0] == "atom":
            d["atoms"].append((f[2], f[3], int(f[4]), f[5], f[6]))
        elif f[0] == "cell":
            d["cells"].append([float(x) for x in f[2:8]])
            d["xyz"].append([])
        elif f[0] == "xyz":
            d["xyz"][int(f[1])].append([float(x) for x in f[3:6]])
        elif f[0] == "volume":
            d["volumes"].append([float(x) for x in f[2:]])
    return d
