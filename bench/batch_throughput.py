#!/usr/bin/env python3
"""Captures per minute of a batch (lfcam.batch.run) on this machine and on a local Dask cluster of
1 and 2 worker processes, against the floor measured in the same run: one capture alone in this
process. The ratio is each run's wall time per capture over that floor: the engine's overhead (above
1) or its parallel gain (below 1). The cluster is started before its clock starts, as a real one
would be running already. Each row is the median of --repeat runs into fresh folders.

    PYTHONPATH=build/python /usr/bin/python3 bench/batch_throughput.py --lfcam build/lfcam
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import lfcam


def timed(function):
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


def median_time(run, repeat, scratch):
    times = []
    for k in range(repeat):
        output = os.path.join(scratch, f"out-{time.monotonic_ns()}-{k}")  # fresh: nothing to resume
        times.append(timed(lambda: run(output)))
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lfcam", default="build/lfcam", help="the command, for `lfcam synth`")
    parser.add_argument("--captures", type=int, default=16)
    parser.add_argument("--size", type=int, default=96, help="pixels across each view")
    parser.add_argument("--views", type=int, default=7)
    parser.add_argument("--steps", default="refocus:0.5,stack:-1:1:5,depth,edof")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as scratch:
        inputs = os.path.join(scratch, "in")
        os.makedirs(inputs)
        for seed in range(args.captures):
            subprocess.run([args.lfcam, "synth", "-o", os.path.join(inputs, f"c{seed:03d}.lf.h5"), "--views",
                            str(args.views), "--size", str(args.size), "--seed", str(seed)], check=True)
        first = os.path.join(inputs, "c000.lf.h5")
        lfcam.batch.run(first, os.path.join(scratch, "warm-up"), args.steps, jobs=1)
        floor = median_time(lambda out: lfcam.batch.run(first, out, args.steps, jobs=1), args.repeat, scratch)

        rows = [("one capture alone (the floor)", 1, floor)]
        for jobs in (1, 2):
            rows.append((f"this machine, --jobs {jobs}", args.captures,
                         median_time(lambda out: lfcam.batch.run(inputs, out, args.steps, jobs=jobs), args.repeat,
                                     scratch)))
        from distributed import Client, LocalCluster
        for workers in (1, 2):
            with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                              dashboard_address=None) as cluster, Client(cluster) as client:
                lfcam.batch.run(first, os.path.join(scratch, f"warm-up-{workers}"), args.steps, client=client)
                rows.append((f"Dask, {workers} local worker{'s' if workers > 1 else ''}", args.captures,
                             median_time(lambda out: lfcam.batch.run(inputs, out, args.steps, client=client),
                                         args.repeat, scratch)))

    print(f"{args.captures} captures of {args.views}x{args.views} views of {args.size}x{args.size}, steps "
          f"{args.steps}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}; median of {args.repeat}")
    print("| run | captures | wall s | captures per minute | s per capture / floor |")
    print("|---|---|---|---|---|")
    for name, count, seconds in rows:
        print(f"| {name} | {count} | {seconds:.2f} | {60 * count / seconds:.1f} | {seconds / count / floor:.2f} |")


if __name__ == "__main__":
    main()
