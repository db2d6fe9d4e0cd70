#!/usr/bin/python3
"""test_ss_dssp.py: molscope's secondary structure (`mol ssrecalc`, DSSP in src/ss) against
mkdssp, an independent DSSP (Debian package `dssp`), run live on the structures in
tests/data; the files are prepared for mkdssp as tests/python/dssp_refs.py describes.
Each structure passes when at least 95% of its residues get the same of the eight codes
(mkdssp's S, P and blank counting as coil). Prints PASS:/FAIL:/SKIP: lines."""
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dssp_refs  # noqa: E402

MOLSCOPE = os.environ.get("MOLSCOPE", "src/molscope")
SCRIPT = """mol new {%s} waitfor all
mol ssrecalc top
set sel [atomselect top "protein and name CA"]
foreach c [$sel get chain] r [$sel get resid] i [$sel get insertion] s [$sel get structure] {
    puts "SS {$c} $r {$i} $s"
}
quit
"""


def molscope_ss(path, tmp):
    """{(chain, resid, insertion): code} from molscope."""
    script = os.path.join(tmp, "ss.tcl")
    with open(script, "w") as f:
        f.write(SCRIPT % path)
    out = subprocess.run([MOLSCOPE, "-dispdev", "text", "-e", script],
                         stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=120)
    if out.returncode != 0:
        raise RuntimeError("molscope failed: %s %s" % (out.stdout[-300:], out.stderr[-300:]))
    got = {}
    for line in out.stdout.splitlines():
        if line.startswith("SS "):
            body = line[3:]
            chain, rest = body[1:].split("}", 1)
            resid, rest = rest.split(None, 1)
            ins, code = rest[1:].split("}", 1)
            got[(chain, int(resid), ins)] = code.strip()
    return got


def main():
    if shutil.which("mkdssp") is None:
        print("SKIP: ss_dssp: mkdssp is not installed (Debian package dssp)")
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        for name in dssp_refs.FILES:
            try:
                ref = dssp_refs.run_mkdssp(name, tmp)
                got = molscope_ss(os.path.join(dssp_refs.DATA, name + ".pdb"), tmp)
            except (subprocess.CalledProcessError, RuntimeError) as e:
                print("FAIL: ss_dssp: %s: %s" % (name, e))
                continue
            same = sum(got.get((c, r, i)) == s for c, r, i, s in ref)
            ok = ref and same * 100 >= 95 * len(ref)
            print("%s: ss_dssp: %s: %d of %d residues as mkdssp" %
                  ("PASS" if ok else "FAIL", name, same, len(ref)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
