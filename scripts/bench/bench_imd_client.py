#!/usr/bin/python3
"""bench_imd_client.py: the peer of bench_imd.sh: a minimal IMD client in Python (socket and
numpy), receiving the same frames as molscope: handshake, IMD_GO, then each IMD_FCOORDS
read into one buffer and copied into the current frame's array (keep 0) or appended as a
new array (keep 1), until the last frame's coordinates (after its energies). Prints
"peer <keep> <frames> <seconds> <cpu-seconds>".

usage: bench_imd_client.py <port> <natoms> <frames> <keep>
"""
import socket
import struct
import sys
import time

import numpy as np


def recv_into(conn, view):
    got = 0
    while got < len(view):
        n = conn.recv_into(view[got:])
        if not n:
            raise EOFError("the server closed")
        got += n


def main():
    port, natoms, frames, keep = (int(a) for a in sys.argv[1:5])
    c0, t0 = time.process_time(), time.perf_counter()
    conn = socket.create_connection(("127.0.0.1", port))
    head = bytearray(8)
    recv_into(conn, memoryview(head))
    order = "<" if struct.unpack("<i", head[4:])[0] == 2 else ">"
    conn.sendall(struct.pack(">ii", 3, 0))
    body = bytearray(12 * natoms)
    current = np.zeros((natoms, 3), dtype=np.float32)
    kept = []
    energies = bytearray(40)
    step = 0
    while True:
        recv_into(conn, memoryview(head))
        kind, length = struct.unpack(">ii", head)
        if kind == 2:
            recv_into(conn, memoryview(body))
            xyz = np.frombuffer(body, dtype=order + "f4").reshape(natoms, 3)
            if keep:
                kept.append(xyz.astype(np.float32))
            else:
                current[:] = xyz
            if step >= 10 * frames:
                break
        elif kind == 1:
            recv_into(conn, memoryview(energies))
            step = struct.unpack(order + "i", energies[:4])[0]
    t, c = time.perf_counter() - t0, time.process_time() - c0
    conn.sendall(struct.pack(">ii", 0, 0))
    conn.close()
    print("peer %d %d %.4f %.4f" % (keep, frames, t, c))


if __name__ == "__main__":
    main()
