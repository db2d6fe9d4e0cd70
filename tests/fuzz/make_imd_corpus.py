#!/usr/bin/python3
"""make_imd_corpus.py: write the seed corpus of the IMD decoder's fuzz target
(tests/fuzz/corpus/imd; fuzz_imd.c says how an input is read: byte 0 the atom count and byte
order, byte 1 the piece size, then a handshake and a stream as a simulation sends it).

usage: tests/fuzz/make_imd_corpus.py [folder]   (default: tests/fuzz/corpus/imd)
"""
import os
import struct
import sys


def header(kind, length):
    return struct.pack(">ii", kind, length)


def frame(n, k, order):
    return header(2, n) + struct.pack(order + "%df" % (3 * n), *[k + i * 0.5 for i in range(3 * n)])


def energies(order):
    return header(1, 1) + struct.pack(order + "i9f", 10, *[float(j) for j in range(9)])


HS_LE = struct.pack(">i", 4) + struct.pack("<i", 2)
HS_BE = struct.pack(">i", 4) + struct.pack(">i", 2)
SEEDS = {
    # a frame, energies, pause, disconnect, little-endian, whole
    "seed01": bytes([3, 255]) + HS_LE + frame(3, 1, "<") + energies("<") + header(7, 0)
    + header(0, 0),
    # big-endian bodies, pieces of 1 byte
    "seed02": bytes([3 | 8, 0]) + HS_BE + frame(3, 1, ">") + energies(">") + frame(3, 2, ">"),
    # no atoms, a rate and a kill
    "seed03": bytes([0, 4]) + HS_LE + frame(0, 1, "<") + header(8, 5) + header(5, 0),
    # a huge coordinate count
    "seed04": bytes([2, 16]) + HS_LE + header(2, 2147483647) + b"\0" * 16,
    # a frame cut short
    "seed05": bytes([7, 1]) + HS_LE + frame(7, 3, "<")[:50],
    # an unknown type, an I/O error, a force message
    "seed06": bytes([1, 7]) + HS_LE + header(99, 0) + header(9, 0) + header(6, 3),
}


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "tests/fuzz/corpus/imd"
    os.makedirs(folder, exist_ok=True)
    for name, data in SEEDS.items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
