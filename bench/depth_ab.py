#!/usr/bin/env python3
"""`lfcam depth` (and `lfcam edof --depth` after it) as whole processes, two builds alternately.

On a shared machine a build's pace swings from one minute to the next, so two builds are compared
in one run, A then B then A ..., each row the median of the runs (after one warm-up run of each:
page cache, lazily loaded libraries), wall clock and CPU seconds (user + system, all threads).

    bench/depth_ab.py --a OTHER/build/lfcam [--b build/lfcam] [--data ../shared/data]
                      [--scene hci-antinous] [--runs 5]
"""
import argparse
import os
import statistics
import tempfile

from whole_process import time_once


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--a", required=True, help="the build compared against (its lfcam)")
    parser.add_argument("--b", default=os.path.join(root, "build", "lfcam"))
    parser.add_argument("--data", default=os.environ.get("LFCAM_DATA_DIR", os.path.join(root, "..", "shared", "data")))
    parser.add_argument("--scene", default="hci-antinous")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    scene = os.path.join(args.data, args.scene)
    with tempfile.TemporaryDirectory(prefix="lfcam-ab-") as work:
        def depth(lfcam, name):
            return [lfcam, "depth", scene, "-o", os.path.join(work, name + ".pfm")]

        def edof(lfcam, name):
            return [lfcam, "edof", scene, "--depth", os.path.join(work, name + ".pfm"),
                    "-o", os.path.join(work, name + ".png")]

        builds = {"A": args.a, "B": args.b}
        times = {(name, step): [] for name in builds for step in ("depth", "edof")}
        for run in range(args.runs + 1):
            for name, lfcam in builds.items():
                depth_time = time_once(depth(lfcam, name))
                edof_time = time_once(edof(lfcam, name))
                if run > 0:  # the first is the warm-up
                    times[(name, "depth")].append(depth_time)
                    times[(name, "edof")].append(edof_time)
        print(f"{args.scene}: median of {args.runs} alternating runs after a warm-up")
        print(f"{'build':<6}{'depth s':>9}{'cpu s':>8}{'+ edof s':>10}{'cpu s':>8}")
        medians = {}
        for name in builds:
            d, e = times[(name, "depth")], times[(name, "edof")]
            both = [x[0] + y[0] for x, y in zip(d, e)]
            both_cpu = [x[1] + y[1] for x, y in zip(d, e)]
            medians[name] = (statistics.median(t[0] for t in d), statistics.median(both))
            print(f"{name:<6}{medians[name][0]:>9.3f}{statistics.median(t[1] for t in d):>8.3f}"
                  f"{medians[name][1]:>10.3f}{statistics.median(both_cpu):>8.3f}")
        print(f"A / B: depth {medians['A'][0] / medians['B'][0]:.2f}x, "
              f"depth + edof {medians['A'][1] / medians['B'][1]:.2f}x")


if __name__ == "__main__":
    main()
