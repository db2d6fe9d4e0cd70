#!/usr/bin/python3
"""imdserver.py: a fake IMD (Interactive Molecular Dynamics) simulation for molscope's tests.

It listens on 127.0.0.1 (a free port), prints the port on the first line of stdout, takes
one client, speaks IMD version 2 as NAMD does (the handshake's version in the server's own
byte order, bodies in that order too) and sends known frames: frame k (1, 2, ...) puts atom
i at (k + 0.5 i, -k, 0.25 i + 0.125 k), after IMD_ENERGIES (as GROMACS orders them) with step 10 k,
temperature 300 + k and energy -1000.5 + k (the other seven terms 1.5, 2.5 ... 7.5).
Then it records every message the client sends, one line each on stdout ("GO", "PAUSE",
"TRATE 5", "DISCONNECT", "KILL", "EOF" when the client closes), and exits after
IMD_DISCONNECT, IMD_KILL or the end of the connection.

usage: imdserver.py [--natoms N] [--frames K] [--mode MODE] [--swap] [--every S]
                    [--after-go-wait SECONDS] [--same]
  --mode normal (default), bye (IMD_DISCONNECT after the frames), wrongcount (frames of
    N + 1 atoms), truncated (half a frame, then close), huge (an IMD_FCOORDS header of
    2147483647 atoms), unknown (message type 99), badhandshake (IMD_FCOORDS where the
    handshake goes), version3 (handshake version 3), silent (never a handshake), close
    (close right after accepting), ioerror (IMD_IOERROR)
  --swap: the other byte order than this machine's for the handshake and the bodies
  --every S: send one more frame every S seconds until the client leaves (after the K)
  --same: every frame has frame 1's coordinates (made once: for benchmarks), the energies
    still count the frames
"""
import argparse
import select
import socket
import struct
import sys
import time

TYPES = ["DISCONNECT", "ENERGIES", "FCOORDS", "GO", "HANDSHAKE", "KILL", "MDCOMM", "PAUSE",
         "TRATE", "IOERROR"]
DISCONNECT, ENERGIES, FCOORDS, GO, HANDSHAKE, KILL, MDCOMM, PAUSE, TRATE, IOERROR = range(10)


def header(kind, length):
    return struct.pack(">ii", kind, length)


def coords(k, natoms, order):
    xyz = []
    for i in range(natoms):
        xyz += [k + 0.5 * i, -float(k), 0.25 * i + 0.125 * k]
    return header(FCOORDS, natoms) + struct.pack(order + "%df" % (3 * natoms), *xyz)


def energies(k, order):
    return header(ENERGIES, 1) + struct.pack(order + "i9f", 10 * k, 300.0 + k, -1000.5 + k,
                                             *[j + 1.5 for j in range(7)])


def frame(k, natoms, order):
    return energies(k, order) + coords(k, natoms, order)


def recv_exact(conn, n):
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        if not chunk:
            return None
        data += chunk
    return data


def say(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def record(conn, timeout):
    """Read one client message within timeout: its line, None at the end, "" on timeout."""
    ready, _, _ = select.select([conn], [], [], timeout)
    if not ready:
        return ""
    h = recv_exact(conn, 8)
    if h is None:
        return None
    kind, length = struct.unpack(">ii", h)
    name = TYPES[kind] if 0 <= kind < len(TYPES) else "TYPE%d" % kind
    return "%s %d" % (name, length) if kind == TRATE else name


def start(conn, args, order):
    """The handshake (or the misbehaviour asked for): whether to go on."""
    mode = args.mode
    if mode == "close":
        return False
    if mode == "silent":
        time.sleep(args.after_go_wait or 8)
        return False
    if mode == "badhandshake":
        conn.sendall(header(FCOORDS, 2))
        return False
    version = 3 if mode == "version3" else 2
    conn.sendall(struct.pack(">i", HANDSHAKE) + struct.pack(order + "i", version))
    line = record(conn, 10)
    if line:
        say(line)
    return line == "GO"


def misbehave(conn, args, order):
    """The broken streams: whether one was sent."""
    n, mode = args.natoms, args.mode
    if mode == "wrongcount":
        conn.sendall(frame(1, n + 1, order))
    elif mode == "truncated":
        conn.sendall(frame(1, n, order)[: 48 + 8 + 6 * n])
    elif mode == "huge":
        conn.sendall(header(FCOORDS, 2147483647) + b"\0" * 64)
    elif mode == "unknown":
        conn.sendall(header(99, 0))
    elif mode == "ioerror":
        conn.sendall(header(IOERROR, 0))
    else:
        return False
    return True


def serve(conn, args):
    native = "<" if sys.byteorder == "little" else ">"
    other = ">" if native == "<" else "<"
    order = other if args.swap else native
    if not start(conn, args, order):
        return
    if misbehave(conn, args, order):
        time.sleep(0.5)
        return
    same = coords(1, args.natoms, order) if args.same else None
    for k in range(1, args.frames + 1):
        if same:
            conn.sendall(energies(k, order))
            conn.sendall(same)
        else:
            conn.sendall(frame(k, args.natoms, order))
    if args.mode == "bye":
        conn.sendall(header(DISCONNECT, 0))
        return
    k = args.frames
    while True:
        line = record(conn, args.every if args.every else 30)
        if line == "" and args.every:
            k += 1
            conn.sendall(frame(k, args.natoms, order))
            continue
        say(line if line else ("EOF" if line is None else "TIMEOUT"))
        if line in (None, "", "DISCONNECT", "KILL"):
            return


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--natoms", type=int, default=3)
    p.add_argument("--frames", type=int, default=1)
    p.add_argument("--mode", default="normal")
    p.add_argument("--swap", action="store_true")
    p.add_argument("--every", type=float, default=0)
    p.add_argument("--after-go-wait", type=float, default=0)
    p.add_argument("--same", action="store_true")
    args = p.parse_args()
    srv = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    srv.bind(("127.0.0.1", 0))
    srv.listen(1)
    say(str(srv.getsockname()[1]))
    srv.settimeout(30)
    try:
        conn, _ = srv.accept()
    except socket.timeout:
        say("NOCLIENT")
        return
    conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    try:
        serve(conn, args)
    except (BrokenPipeError, ConnectionResetError):
        say("RESET")
    conn.close()


if __name__ == "__main__":
    main()
