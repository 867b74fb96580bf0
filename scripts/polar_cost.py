#!/usr/bin/python3
"""What a polar (Cosserat) step and run cost against nonpolar ones (issue 15 item 4), in one
sitting: the step benchmarks in interleaved rounds (scripts/bench_interleaved.sh), then the
default flat blade, nonpolar and polar in turn. Prints per-round ratios and their medians.

Two polar steps are timed against the Mohr-Coulomb one, as plain and fused MUSL:
  cosserat_drucker_prager      the paper's micro-inertia: its stable step is 2.8e-5 s against
                               8.0e-5 s, so its 1000 timed steps end earlier in the block's
                               settling, with 0.47 of its points plastic against 0.25;
  cosserat_drucker_prager_j16  the micro-inertia x 16 of the flat blade's polar default: the
                               step 7.5e-5 s, 0.29 plastic; the like-for-like step.
The flat blade's ratio per step divides each run's wall time by its step count (summary.csv):
the polar run takes 6 % more steps (the skew shear wave is faster than the p-wave).

usage: scripts/polar_cost.py [--build DIR] [--rounds N] [--core C] [--skip-runs]
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile

SCHEMES = ("MUSL", "FusedMUSL")
POLAR = ("cosserat_drucker_prager", "cosserat_drucker_prager_j16")


def require_binary(binary, option):
    if not os.access(binary, os.X_OK):
        sys.exit(f"polar_cost.py: {binary} not found; configure the build with {option} and "
                 "build it (README, 'Benchmarks')")


def step_ratios(build, rounds, core):
    binary = os.path.join(build, "benchmarks", "cosmpm_bench_simulation")
    require_binary(binary, "-DCOSMPM_BUILD_BENCHMARKS=ON")
    pattern = "^step/linear/(Fused)?MUSL/(mohr_coulomb|" + "|".join(POLAR) + ")/1/"
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bench_interleaved.sh")
    out = subprocess.run([script, "-r", str(rounds), "-c", str(core), "-f", pattern,
                          f"now={binary}"], check=True, capture_output=True, text=True).stdout
    rows = {}
    for row in csv.reader(out.splitlines()[1:]):
        name = row[0].split("/1/")[0]  # step/linear/<scheme>/<model>
        rows[name] = [float(v) for v in row[3].split()]
    print("step (one thread, ms): median of the round medians; polar / nonpolar per round")
    for scheme in SCHEMES:
        nonpolar = rows[f"step/linear/{scheme}/mohr_coulomb"]
        print(f"  {scheme} mohr_coulomb {statistics.median(nonpolar) / 1e6:.4f}")
        for polar in POLAR:
            times = rows[f"step/linear/{scheme}/{polar}"]
            ratios = [p / n for p, n in zip(times, nonpolar)]
            print(f"  {scheme} {polar} {statistics.median(times) / 1e6:.4f}, ratio "
                  f"{min(ratios):.3f}-{max(ratios):.3f}, median {statistics.median(ratios):.3f}")


def run_once(binary, core, polar, out):
    command = ["taskset", "-c", str(core), binary, "--threads", "1", "--frames", "false",
               "--out", out]
    if polar:
        command += ["--polar", "true"]
    environment = dict(os.environ, OMP_WAIT_POLICY="passive")
    subprocess.run(command, check=True, env=environment, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.csv")) as summary:
        row = next(csv.DictReader(summary))
    return float(row["run_seconds"]), int(row["steps"])


def run_ratios(build, rounds, core):
    binary = os.path.join(build, "examples", "example_03_flat_blade")
    require_binary(binary, "-DCOSMPM_BUILD_EXAMPLES=ON")
    runs, steps = [], []
    with tempfile.TemporaryDirectory() as scratch:
        for round_number in range(rounds):
            pair = [run_once(binary, core, polar,
                             os.path.join(scratch, f"{round_number}_{'polar' if polar else 'nonpolar'}"))
                    for polar in (False, True)]
            runs.append(pair[1][0] / pair[0][0])
            steps.append((pair[1][0] / pair[1][1]) / (pair[0][0] / pair[0][1]))
            print(f"  round {round_number + 1}: nonpolar {pair[0][0]:.2f} s ({pair[0][1]} steps), "
                  f"polar {pair[1][0]:.2f} s ({pair[1][1]} steps)", file=sys.stderr)
    print("default flat blade (one thread, frames off), polar / nonpolar per round:")
    print(f"  run {min(runs):.3f}-{max(runs):.3f}, median {statistics.median(runs):.3f}")
    print(f"  per step {min(steps):.3f}-{max(steps):.3f}, median {statistics.median(steps):.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--core", type=int, default=1)
    parser.add_argument("--skip-runs", action="store_true", help="the step benchmarks only")
    args = parser.parse_args()
    if args.rounds < 1:
        sys.exit(f"polar_cost.py: --rounds {args.rounds}: must be at least 1")
    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    step_ratios(args.build, args.rounds, args.core)
    if not args.skip_runs:
        run_ratios(args.build, args.rounds, args.core)
    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
