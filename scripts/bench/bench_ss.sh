#!/usr/bin/env bash
# bench_ss.sh: the secondary structure benchmark. ms_ss_compute on 1tii replicated to 1M and
# 2M atoms (scripts/bench/replicate.py, into bench-out/) and on 1tii itself, beside mkdssp
# (Debian package dssp) on 1tii where it is installed. Run from a built tree:
#   scripts/bench/bench_ss.sh [repeats]
set -euo pipefail
cd "$(dirname "$0")/../.."
repeats=${1:-5}
make -s scripts/bench/bench_ss
mkdir -p bench-out
for n in 1000000 2000000; do
    f=bench-out/1tii_$n.pdb
    [ -f "$f" ] || /usr/bin/python3 scripts/bench/replicate.py tests/data/1tii.pdb $n "$f"
done
for f in tests/data/1tii.pdb bench-out/1tii_1000000.pdb bench-out/1tii_2000000.pdb; do
    scripts/bench/bench_ss "$f" "$repeats"
done
if command -v mkdssp > /dev/null; then
    /usr/bin/python3 - "$repeats" <<'PY'
import os, subprocess, sys, tempfile, time
sys.path.insert(0, "tests/python")
import dssp_refs
with tempfile.TemporaryDirectory() as tmp:
    src, dst = os.path.join(tmp, "1tii.pdb"), os.path.join(tmp, "1tii.dssp")
    dssp_refs.mkdssp_input("tests/data/1tii.pdb", src)
    times = []
    for _ in range(int(sys.argv[1])):
        t0 = time.monotonic()
        subprocess.run(["mkdssp", "--output-format", "dssp", src, dst], check=True,
                       capture_output=True)
        times.append(time.monotonic() - t0)
    times.sort()
    print("mkdssp on 1tii (whole program: read, DSSP, accessibility, write): median "
          "%.1f ms, best %.1f ms (%d runs)" % (1e3 * times[len(times) // 2], 1e3 * times[0],
                                               len(times)))
PY
else
    echo "mkdssp is not installed (Debian package dssp): no comparison"
fi
