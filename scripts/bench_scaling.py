#!/usr/bin/env python3
"""Two threads against one, each round beside the host's own control loops.

On this shared VM whether two threads can scale at all changes from minute to minute: the
host sometimes runs the two vCPUs where data moved between them costs twice as much, or on
one core (docs/performance.md, "Two threads and the host"). A two-thread figure therefore
means something about our code only beside a control measured in the same minute. Each round
runs the host controls (benchmarks/host/scaling.bench.cpp: throughput_loop, plain_loop,
cache_halves and cache_halves_swapped) on one and two threads, then every selected step benchmark on one and two threads, all unpinned with
OpenMP's default wait policy; the scaling of a benchmark is its two-thread items_per_second
over its one-thread figure. Printed: every round, then per benchmark the median scaling over
all rounds and over the rounds in which the throughput control scaled by at least --control.

usage: scripts/bench_scaling.py [--rounds 5] [--control 1.8]
           [--filter 'step/linear/(USL|MUSL/mohr_coulomb|MUSL/cosserat_drucker_prager)/[12]/']
           [--build build/release]
"""
import argparse
import csv
import io
import os
import re
import statistics
import subprocess
import sys
import time


def run(binary, benchmark_filter, repetitions):
    """Median items_per_second by benchmark name, the thread argument kept."""
    env = dict(os.environ)
    env.pop("OMP_WAIT_POLICY", None)
    out = subprocess.run(
        [binary, f"--benchmark_filter={benchmark_filter}",
         f"--benchmark_repetitions={repetitions}", "--benchmark_report_aggregates_only=true",
         "--benchmark_format=csv"],
        env=env, check=True, capture_output=True, text=True).stdout
    medians = {}
    for row in csv.DictReader(io.StringIO(out)):
        name = row["name"]
        if name.endswith("_median"):
            medians[name[: -len("_median")]] = float(row["items_per_second"])
    if not medians:
        sys.exit(f"{binary}: no benchmark matches '{benchmark_filter}'")
    return medians


def scaling(medians):
    """Two-thread over one-thread figure, keyed by the name without its thread argument."""
    pairs = {}
    for name, rate in medians.items():
        match = re.match(r"^(.*)/([12])(/.*)?$", name)
        if not match:
            continue
        key = match.group(1) + (match.group(3) or "").replace("/real_time", "")
        pairs.setdefault(key, {})[int(match.group(2))] = rate
    return {key: p[2] / p[1] for key, p in pairs.items() if 1 in p and 2 in p}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--control", type=float, default=1.8)
    parser.add_argument(
        "--filter",
        default="step/linear/(USL|MUSL/mohr_coulomb|MUSL/cosserat_drucker_prager)/[12]/")
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--repetitions", type=int, default=3)
    args = parser.parse_args()
    host = os.path.join(args.build, "benchmarks", "cosmpm_bench_host")
    steps = os.path.join(args.build, "benchmarks", "cosmpm_bench_simulation")
    rounds = []
    print(f"uptime before: {os.getloadavg()}", file=sys.stderr)
    for r in range(1, args.rounds + 1):
        control = scaling(run(host, "host/", args.repetitions))
        measured = scaling(run(steps, args.filter, args.repetitions))
        rounds.append((control, measured))
        line = ", ".join(f"{k} {v:.2f}" for k, v in {**control, **measured}.items())
        print(f"round {r} ({time.strftime('%H:%M:%S')}): {line}", flush=True)
    print(f"uptime after: {os.getloadavg()}", file=sys.stderr)
    good = [m for c, m in rounds if c.get("host/throughput_loop", 0) >= args.control]
    print(f"\nscaling (two threads / one), median over rounds; {len(good)} of {len(rounds)} rounds "
          f"had host/throughput_loop >= {args.control}")
    print("benchmark,all rounds,control-scaled rounds")
    for key in sorted({k for c, m in rounds for k in {**c, **m}}):
        every = [r.get(key) for c, m in rounds for r in (c, m) if key in r]
        chosen = [m[key] for m in good if key in m] if not key.startswith("host/") else []
        chosen_text = f"{statistics.median(chosen):.2f}" if chosen else "-"
        print(f"{key},{statistics.median(every):.2f},{chosen_text}")


if __name__ == "__main__":
    main()
