"""mstest.py: what the cross-check scripts share: PASS/FAIL/SKIP lines as tests/run-tests
counts them, and the output of tests/tools/msdump (the molecule as molscope loads it)."""
import subprocess


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
