#!/usr/bin/env python3
"""Whole-process times of lfcam commands, each against a floor timed in the same run.

A user runs a command, not a kernel: these are wall-clock times of whole processes (start-up,
reading, work, writing), the median of several runs after one warm-up run (files in the page
cache), and the CPU time the process used (user + system, all its threads), which other jobs on a
shared machine disturb far less. Each row is compared with a floor measured alongside it, so the
ratio holds on a noisy or shared machine:
  - start-up rows: bench/process_floor.c, a C program that does nothing;
  - rows that read files: bench/read_floor.c, which reads the same bytes and copies them once.

    bench/whole_process.py [--lfcam build/lfcam] [--floors build/bench] [--data ../shared/data]
                           [--runs 5] [--only ROW,...]
"""
import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def children_cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def time_once(command):
    """Wall-clock and CPU seconds of one run."""
    cpu = children_cpu_seconds()
    start = time.perf_counter()
    finished = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    elapsed = time.perf_counter() - start
    if finished.returncode != 0:
        sys.exit(f"whole_process.py: {' '.join(command)} failed ({finished.returncode}): "
                 f"{finished.stderr.decode(errors='replace').strip()}")
    return elapsed, children_cpu_seconds() - cpu


def median_time(command, runs):
    """Medians of the wall-clock and of the CPU seconds."""
    time_once(command)  # warm-up: page cache, lazily loaded libraries
    times = [time_once(command) for _ in range(runs)]
    return statistics.median(t[0] for t in times), statistics.median(t[1] for t in times)


def files_in(folder):
    return sorted(os.path.join(folder, name) for name in os.listdir(folder)
                  if os.path.isfile(os.path.join(folder, name)))


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lfcam", default=os.path.join(root, "build", "lfcam"))
    parser.add_argument("--floors", default=os.path.join(root, "build", "bench"),
                        help="folder holding process_floor and read_floor (built with -DLFCAM_BUILD_BENCH=ON)")
    parser.add_argument("--data", default=os.environ.get("LFCAM_DATA_DIR", os.path.join(root, "..", "shared", "data")))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--only", default="", help="comma-separated row names (default: every row)")
    args = parser.parse_args()

    lfcam = args.lfcam
    process_floor = os.path.join(args.floors, "process_floor")
    read_floor = os.path.join(args.floors, "read_floor")
    for program in (lfcam, process_floor, read_floor):
        if not os.access(program, os.X_OK):
            sys.exit(f"whole_process.py: {program} is missing (build with -DLFCAM_BUILD_BENCH=ON)")
    hci = os.path.join(args.data, "hci-antinous")
    guv = os.path.join(args.data, "lfm-guv")
    for folder in (hci, guv):
        if not os.path.isdir(folder):
            sys.exit(f"whole_process.py: {folder} is absent (see the data's SOURCES.md, or pass --data)")

    work = tempfile.mkdtemp(prefix="lfcam-bench-")
    native = os.path.join(work, "antinous.lf.h5")
    hci_files = files_in(hci)
    guv_raw = [os.path.join(guv, name) for name in
               ("Lightfield_GUVExperim1.tif", "Radiometry_GUVExperim1.tif", "DarkFrame_GUVExperim1.tif")]
    slopes = ["--slopes=-2:2:16"]
    # name, command, floor command, goal in seconds (issue 21's table)
    rows = [
        ("help", [lfcam, "--help"], [process_floor], 0.02),
        ("info", [lfcam, "info", hci], [process_floor], 0.05),
        ("decode-guv", [lfcam, "decode", guv_raw[0], "--white", guv_raw[1], "--dark", guv_raw[2], "--bayer", "mono",
                        "-o", os.path.join(work, "guv.lf.h5")], [read_floor] + guv_raw, 0.08),
        ("stack-png", [lfcam, "stack", hci] + slopes + ["-o", os.path.join(work, "stack-png")],
         [read_floor] + hci_files, 0.8),
        ("convert", [lfcam, "convert", hci, "-o", native], [read_floor] + hci_files, 1.0),
        ("stack-native", [lfcam, "stack", native] + slopes + ["-o", os.path.join(work, "stack-native")],
         [read_floor, native], None),  # goal: faster than stack-png
    ]
    only = set(filter(None, args.only.split(",")))
    try:
        print(f"whole processes, median of {args.runs} runs after a warm-up; floors timed in the same run")
        print(f"{'row':<14}{'lfcam s':>10}{'cpu s':>8}{'floor s':>10}{'ratio':>8}{'goal s':>9}")
        measured = {}
        for name, command, floor, goal in rows:
            if only and name not in only:
                continue
            if name == "stack-native" and not os.path.exists(native):
                time_once(rows[4][1])  # the native file comes from the convert row
            seconds, cpu_seconds = median_time(command, args.runs)
            floor_seconds, _ = median_time(floor, args.runs)
            measured[name] = seconds
            goal_text = f"{goal:.2f}" if goal else "<png"
            print(f"{name:<14}{seconds:>10.3f}{cpu_seconds:>8.3f}{floor_seconds:>10.4f}{seconds / floor_seconds:>8.1f}"
                  f"{goal_text:>9}")
        if os.path.exists(native):
            png_bytes = sum(os.path.getsize(path) for path in hci_files if path.endswith(".png"))
            native_bytes = os.path.getsize(native)
            print(f"native size: {native_bytes / 1e6:.1f} MB for {png_bytes / 1e6:.1f} MB of PNGs "
                  f"(ratio {native_bytes / png_bytes:.2f}, goal <= 1)")
        if "stack-png" in measured and "stack-native" in measured:
            print(f"stack from the native file / from PNGs: {measured['stack-native'] / measured['stack-png']:.2f} "
                  "(goal < 1)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
