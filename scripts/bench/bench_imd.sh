#!/usr/bin/env bash
# bench_imd.sh: IMD streaming: frames per second molscope receives from a simulation of
# natoms atoms (the fake one of the tests, tests/python/imdserver.py --same, on 127.0.0.1),
# with `imd keep 0` (each frame replaces the last) and `imd keep 1` (each frame appended),
# beside a minimal Python client (bench_imd_client.py: socket and numpy) receiving the same
# stream. Best of 3 runs; wall time and the receiving process's CPU time (one thread: IMD is
# read on the Tcl event loop).
#   scripts/bench/bench_imd.sh [build-folder]   NATOMS (100000) FRAMES (200)
set -eu
. "$(dirname "$0")/lib.sh" "$@"
natoms=${NATOMS:-100000}
frames=${FRAMES:-200}
export MOLSCOPE_TCLLIB=$src/tcl MOLSCOPE_PLUGINDIR=$build/plugins/.libs
server=$src/tests/python/imdserver.py

# peer <keep>: one run of the Python client
peer() {
    local fifo port spid
    fifo=$(mktemp -u) && mkfifo "$fifo"
    /usr/bin/python3 "$server" --natoms $natoms --frames $frames --same >"$fifo" & spid=$!
    exec 3<"$fifo"
    read -r port <&3
    /usr/bin/python3 "$src/scripts/bench/bench_imd_client.py" $port $natoms $frames $1
    cat <&3 >/dev/null
    exec 3<&-
    wait $spid || true
    rm -f "$fifo"
}
ours() {
    "$build/src/molscope" -dispdev text -e "$src/scripts/bench/bench_imd.tcl" \
        -args "$server" $natoms $frames $1 </dev/null 2>/dev/null | grep '^imd '
}
# best <lines>: the run with the least wall time
best() { sort -k4 -g | head -1; }

echo "== IMD: $frames frames of $natoms atoms ($(( 12 * natoms * frames / 1000000 )) MB) from the fake simulation"
for keep in 0 1; do
    m=$(for i in 1 2 3; do ours $keep; done | best)
    p=$(for i in 1 2 3; do peer $keep; done | best)
    read -r _ _ _ mt mc _ <<<"$m"
    read -r _ _ _ pt pc <<<"$p"
    awk -v k=$keep -v f=$frames -v mt=$mt -v mc=$mc -v pt=$pt -v pc=$pc 'BEGIN{
        printf "   keep %d: molscope %.0f frames/s (%.3f s, cpu %.2f s); Python client %.0f frames/s (%.3f s, cpu %.2f s)\n",
            k, f / mt, mt, mc, f / pt, pt, pc }'
done
