#!/usr/bin/env python3
"""movie_model.py: model the 64-512-node rows of Table 3 of Stone et al., "GPU-Accelerated
Molecular Visualization on Petascale Supercomputing Platforms" (UltraVis'13: a 1,079-frame
movie on Blue Waters) for `movie make`, from times measured by scripts/bench/bench_movie.sh.

    movie_model.py [--tframe S] [--ranks-per-node R] [--script S] [--read S] [--hop S]
                   [--enc-fps F] [--state-mb MB] [--fs-gbs G] [--frames N]

The defaults are the values doc/BENCHMARKS.md took from bench_movie.sh on a 2-core machine.

The model, for N nodes of R ranks each (P = N R ranks), every frame costing the same:
  script loading     the measured per-process time (the launcher's own start-up on N nodes
                     is not measured here and not included)
  state loading      rank 0 reads the files (--read) and broadcasts them down a binomial
                     tree: ceil(log2 P) levels, each costing what one level cost here (--hop:
                     the 2-rank broadcast load minus the 1-rank read); for comparison, every
                     rank reading the files itself from a shared file system of --fs-gbs
                     GB/s in all: --read + P * state / bandwidth
  geometry and       frames are handed out one at a time, so with equal frames the last one
  rendering          ends after ceil(frames / P) frame times (--tframe: one rank's time per
                     frame when R ranks share a node)
  video complete     frames reach the single encoder on rank 0 in order, a round of P at a
                     time; it encodes --enc-fps frames per second: the video is complete when
                     the encoder has worked through every round
  total              script + state + video complete
Then, to compare with the paper's rows, the same rendering and encoding terms with the
paper's own cost per frame and node, one rank per node: its first row's geometry and
rendering time over that row's ceil(frames / nodes) (64 XK7 nodes: 655 s / 17; 256 XE6
nodes: 1374 s / 5), and the encoder at 1920x1080, taken to encode --enc-fps scaled by the
pixels (1280x720 / 1920x1080) frames per second.
"""
import argparse
import math

# Table 3 of the UltraVis'13 paper as reproduced in Table 2 of Stone et al., Parallel
# Computing 55 (2016): HIV-1 capsid, 1920x1080, 144 AO samples per pixel, 1,079 frames;
# (nodes, script load, state load, geometry and rendering, total) in seconds.
PAPER = {
    "XK7 (GPU, TachyonL-OptiX)": [(64, 2, 38, 655, 695), (128, 4, 74, 331, 410),
                                  (256, 7, 110, 171, 288)],
    "XE6 (CPU, Tachyon)": [(256, 7, 160, 1374, 1541), (512, 13, 211, 808, 1032)],
}
NODES = (64, 128, 256, 512)


def encode_done(frames, ranks, tframe, enc_fps):
    """When the single encoder has encoded every frame arriving in rounds of `ranks`."""
    t = 0.0
    for k in range(1, math.ceil(frames / ranks) + 1):
        n = min(ranks, frames - (k - 1) * ranks)
        t = max(t, k * tframe) + n / enc_fps
    return t


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--frames", type=int, default=1079)
    ap.add_argument("--ranks-per-node", type=int, default=2)
    ap.add_argument("--tframe", type=float, default=0.67)
    ap.add_argument("--script", type=float, default=0.4)
    ap.add_argument("--read", type=float, default=0.2)
    ap.add_argument("--hop", type=float, default=0.5)
    ap.add_argument("--enc-fps", type=float, default=20.0)
    ap.add_argument("--state-mb", type=float, default=126.0)
    ap.add_argument("--fs-gbs", type=float, default=10.0)
    ap.add_argument("--enc-pixels", type=float, default=1280 * 720,
                    help="pixels of the frames --enc-fps was measured on")
    a = ap.parse_args()

    print("molscope, this benchmark's movie made %d frames long, %d ranks per node:" %
          (a.frames, a.ranks_per_node))
    print("| nodes | script loading | state loading: bcast (every rank reads) | "
          "geometry and rendering | video complete | total |")
    print("|---|---|---|---|---|---|")
    for n in NODES:
        p = n * a.ranks_per_node
        state = a.read + math.ceil(math.log2(p)) * a.hop
        reads = a.read + p * a.state_mb / 1000.0 / a.fs_gbs
        render = math.ceil(a.frames / p) * a.tframe
        video = encode_done(a.frames, p, a.tframe, a.enc_fps)
        print("| %d | %.1f s | %.1f s (%.1f s) | %.1f s | %.1f s | %.1f s |" %
              (n, a.script, state, reads, render, video, a.script + state + video))

    enc_hd = a.enc_fps * a.enc_pixels / (1920 * 1080)
    print("\nThe paper's rows beside the model's rendering and encoding terms with the paper's "
          "cost per frame and node (encoder at 1920x1080: %.1f frames/s):" % enc_hd)
    print("| machine | nodes | paper: script / state / geometry and rendering / total | "
          "cost per frame and node | ceil(%d / nodes) | model: geometry and rendering | "
          "model: video complete |" % a.frames)
    print("|---|---|---|---|---|---|---|")
    for machine, rows in PAPER.items():
        n0, _, _, r0, _ = rows[0]
        tf = r0 / math.ceil(a.frames / n0)
        for n in sorted(set([r[0] for r in rows] + [512])):
            row = [r for r in rows if r[0] == n]
            paper = "%d / %d / %d / %d s" % row[0][1:] if row else "-"
            k = math.ceil(a.frames / n)
            print("| %s | %d | %s | %.1f s | %d | %.0f s | %.0f s |" %
                  (machine, n, paper, tf, k, k * tf, encode_done(a.frames, n, tf, enc_hd)))

if __name__ == "__main__":
    main()
