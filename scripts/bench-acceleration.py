#!/usr/bin/env python3
"""Speed-up of empty-space skipping and early ray termination, as ratios measured in one run.

For every dataset and transfer function, runs `amrsp render --repeat N` with the four
combinations of --empty-space-skipping on|off and --opacity-threshold 1|0.999, interleaved over
several rounds (so that load from other processes hits every configuration alike), and prints
the median frame time of each configuration and its speed-up over "both off".

usage: scripts/bench-acceleration.py [--amrsp PATH] [--method packing|cpu-kdtree] [--size WxH]
                                     [--frames N] [--rounds R] [--tf LIST] [--extra OPTIONS]
                                     [DATASET[@ARRAY] ...]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data")
DEFAULT_DATASETS = [
    os.path.join(DATA, "enzo_moving7", "DD0010", "moving7_0010.hierarchy") + "@Density",
    os.path.join(DATA, "amrex_plt1_Y") + "@Y(H2)",
    "synthetic:cosmo@",
]
CONFIGS = [("off", "1"), ("on", "1"), ("off", "0.999"), ("on", "0.999")]


def run(amrsp, dataset, array, method, size, frames, extra, tf, skip, threshold):
    cmd = [amrsp, "render", dataset, "--method", method, "--size", size, "--tf", tf,
           "--repeat", str(frames), "--empty-space-skipping", skip,
           "--opacity-threshold", threshold, "--stats", "-o", os.devnull + ".png"]
    if array:
        cmd += ["--array", array]
    cmd += extra.split()
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("amrsp failed: " + " ".join(cmd) + "\n" + out.stderr)
    frames_line = re.search(r"frames: \d+, ms mean ([0-9.eE+-]+), min ([0-9.eE+-]+)", out.stdout)
    stats = re.search(r"stats: (.*)", out.stdout)
    return float(frames_line.group(1)), (stats.group(1) if stats else "")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--amrsp", default=os.path.join(HERE, "..", "build", "paraview", "Tools",
                                                   "amrsp", "amrsp"))
    p.add_argument("--method", default="packing")
    p.add_argument("--size", default="512x512")
    p.add_argument("--frames", type=int, default=4)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--tf", default="sparse,default")
    p.add_argument("--extra", default="", help="further amrsp render options, e.g. "
                   "'--unit-distance 0.001'")
    p.add_argument("datasets", nargs="*", help="DATASET[@ARRAY]")
    a = p.parse_args()
    for spec in a.datasets or DEFAULT_DATASETS:
        dataset, _, array = spec.partition("@")
        for tf in a.tf.split(","):
            times = {c: [] for c in CONFIGS}
            stats = {}
            for _ in range(a.rounds):
                for c in CONFIGS:
                    ms, st = run(a.amrsp, dataset, array, a.method, a.size, a.frames, a.extra,
                                 tf, *c)
                    times[c].append(ms)
                    stats[c] = st
            base = statistics.median(times[("off", "1")])
            print(f"{os.path.basename(dataset.rstrip('/'))} {array or ''} tf={tf} "
                  f"method={a.method} size={a.size} {a.extra} "
                  f"({a.rounds} rounds x {a.frames} frames)")
            for c in CONFIGS:
                med = statistics.median(times[c])
                print(f"  skipping {c[0]:3s} threshold {c[1]:5s}: {med:9.1f} ms  "
                      f"speed-up {base / med:5.2f}  [{stats[c]}]")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
