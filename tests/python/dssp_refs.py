#!/usr/bin/python3
"""dssp_refs.py: how the reference secondary structures in tests/unit/test_ss.c were
obtained, and the helpers tests/python/test_ss_dssp.py uses to compare with mkdssp live.

Run by hand (/usr/bin/python3 tests/python/dssp_refs.py); it is not part of the suite. It
runs mkdssp 4.2.2 (Debian 12 package `dssp`), an independent implementation of Kabsch &
Sander's DSSP, on copies of tests/data/{1tii,il2,pept,helix_amber}.pdb and prints, for each,
the per-residue assignment as C initialisers: runs of consecutive residue numbers of one
chain, a string of codes each.

mkdssp 4.2.2 reads PDB files only in a form close to the wwPDB's, so each copy gets:
  - only its ATOM records (no HELIX/SHEET, so nothing from the file is used; no HETATM
    waters; no TER: mkdssp drops the first atom after a bare TER line),
  - a HEADER and a CRYST1 line (mkdssp refuses a file without HEADER),
  - chain A for a blank chain id, an element symbol where the file has none,
  - the standard names CYS and HIS for Amber's CYX, HID, HIE and HIP (mkdssp leaves
    residues it does not know out of the polymer).
Coordinates are unchanged. mkdssp's eight codes map to molscope's as H G I E B T kept,
S (bend), P (polyproline) and blank to C.
"""
import os
import subprocess
import sys
import tempfile

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
FILES = ["1tii", "il2", "pept", "helix_amber"]
AMBER = {"CYX": "CYS", "HID": "HIS", "HIE": "HIS", "HIP": "HIS"}


def mkdssp_input(src, dst):
    """Write the copy of src mkdssp reads (see above)."""
    out = ["HEADER    TEST                                    01-JAN-00   1ABC",
           "CRYST1    1.000    1.000    1.000  90.00  90.00  90.00 P 1           1"]
    for line in open(src):
        if not line.startswith("ATOM"):
            continue
        line = line.rstrip("\n").ljust(80)
        chain = line[21] if line[21] != " " else "A"
        name = line[12:16]
        el = line[76:78].strip() or name.strip().lstrip("0123456789")[0]
        res = AMBER.get(line[17:20], line[17:20])
        out.append(line[:17] + res + line[20] + chain + line[22:72] + "    " + el.rjust(2))
    out.append("END")
    with open(dst, "w") as f:
        f.write("\n".join(out) + "\n")


def parse_dssp(path):
    """[(chain, resid, insertion, code)] in mkdssp's order, break lines left out."""
    rows, go = [], False
    for line in open(path):
        if line.startswith("  #  RESIDUE"):
            go = True
            continue
        if not go or len(line) < 17 or line[13] == "!":
            continue
        code = line[16] if line[16] in "HGIEBT" else "C"
        rows.append((line[11], int(line[5:10]), line[10].strip(), code))
    return rows


def run_mkdssp(name, tmp):
    """mkdssp's assignment of tests/data/<name>.pdb; chains as in the original file."""
    src = os.path.join(DATA, name + ".pdb")
    blank = any(l.startswith("ATOM") and l[21] == " " for l in open(src))
    pdb, dssp = os.path.join(tmp, name + ".pdb"), os.path.join(tmp, name + ".dssp")
    mkdssp_input(src, pdb)
    subprocess.run(["mkdssp", "--output-format", "dssp", pdb, dssp], check=True,
                   capture_output=True)
    rows = parse_dssp(dssp)
    if blank:   # chain A stood for the blank chain (these files have no real chain A)
        rows = [("" if c == "A" else c, r, i, s) for c, r, i, s in rows]
    return rows


def runs(rows):
    """Runs of consecutive residue numbers in one chain: (chain, first resid, codes)."""
    out = []
    for c, r, ins, s in rows:
        assert not ins, "insertion codes are not expected here"
        if out and out[-1][0] == c and out[-1][1] + len(out[-1][2]) == r:
            out[-1][2] += s
        else:
            out.append([c, r, s])
    return out


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for name in FILES:
            print("/* %s */" % name)
            for c, r, s in runs(run_mkdssp(name, tmp)):
                for k in range(0, len(s), 60):
                    print('    {"%s", %d, "%s"},' % (c, r + k, s[k:k + 60]))


if __name__ == "__main__":
    sys.exit(main())
