#!/usr/bin/env python3
"""Times Google Benchmark contenders in alternating rounds, one process per contender and round.

This VM's speed drifts by ±20 % between processes minutes apart, so one run per contender cannot
decide a ratio of 0.8: each round runs every contender once (--benchmark_repetitions=REPS), and
the table gives each contender's minimum and median over all rounds' repetitions, its median over
the fastest peer's median (the peers: contenders without "limsurf" in their name), and its peak
resident memory (the largest of its processes, from wait4).

Usage: alternate.py BINARY ROUNDS NAME...   (NAME as in --benchmark_filter="BM_NAME/")
e.g.   alternate.py build/ci/bench/bench_refine 4 limsurf_points_CatmullClark/1 CGAL_CatmullClark
"""
import csv
import io
import os
import subprocess
import sys

REPS = 3


def run_once(binary, name):
    """(times in ms of its repetitions, peak resident KiB) of one process."""
    process = subprocess.Popen([binary, "--benchmark_filter=BM_%s/" % name, "--benchmark_repetitions=%d" % REPS,
                                "--benchmark_format=csv"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    out = process.stdout.read()
    _, status, usage = os.wait4(process.pid, 0)
    if status != 0:
        sys.exit("%s failed (status %d)" % (name, status))
    lines = out[out.index("name,"):]
    times = []
    for row in csv.DictReader(io.StringIO(lines)):
        if any(row["name"].endswith(s) for s in ("_mean", "_median", "_stddev", "_cv")):
            continue
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[row["time_unit"]]
        times.append(float(row["real_time"]) * scale)
    return times, usage.ru_maxrss


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    binary, rounds, names = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    times = {name: [] for name in names}
    peak = {name: 0 for name in names}
    for _ in range(rounds):
        for name in names:
            t, kib = run_once(binary, name)
            times[name] += t
            peak[name] = max(peak[name], kib)
    median = {name: sorted(t)[len(t) // 2] for name, t in times.items()}
    peers = [name for name in names if "limsurf" not in name]
    fastest = min((median[name] for name in peers), default=None)
    print("| contender | min (ms) | median (ms) | median / fastest peer's | peak (MiB) |")
    print("|---|---|---|---|---|")
    for name in names:
        ratio = "%.2f" % (median[name] / fastest) if fastest else "—"
        print("| %s | %.0f | %.0f | %s | %d |" % (name, min(times[name]), median[name], ratio, peak[name] // 1024))
    print("(%d rounds × %d repetitions each)" % (rounds, REPS))


if __name__ == "__main__":
    main()
