#!/usr/bin/env python3
"""The composition matrix of issue 13, item 1: the granular collapse of example 04 with every
shape function x update scheme x cell size x particles per cell x velocity transfer.

Runs build/release/examples/example_04_granular_collapse once per composition (one thread,
no frames) into OUT/<tag>/, skipping compositions whose summary.txt already exists, so an
interrupted matrix resumes. Then writes OUT/matrix.csv and OUT/matrix.md (the table of
docs/validation.md, "Granular flow to rest").

  scripts/granular_matrix.py [--out out/granular_matrix] [--floor fixed] [--only-table]
                             [--shapes linear,gimp,quadratic,cubic] [--schemes usl,musl,usf]
                             [--example PATH]
"""
import argparse
import csv
import itertools
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "build", "release", "examples", "example_04_granular_collapse")


def read_summary(path):
    values = {}
    with open(path) as f:
        for line in f:
            if " = " in line:
                key, value = line.rstrip("\n").split(" = ", 1)
                values[key] = value
    return values


def tag(shape, scheme, cell, ppc, flip, floor):
    transfer = "apic" if flip == "apic" else f"flip{float(flip):g}"
    return f"{shape}_{scheme}_h{cell * 1e3:g}mm_ppc{ppc}_{transfer}_{floor}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "granular_matrix"))
    parser.add_argument("--floor", default="fixed", choices=["fixed", "friction"])
    parser.add_argument("--shapes", default="linear,gimp,quadratic,cubic")
    parser.add_argument("--schemes", default="usl,musl,usf")
    parser.add_argument("--cells", default="0.0025,0.005")
    parser.add_argument("--ppcs", default="2,3")
    parser.add_argument("--flips", default="1,0.99",
                        help="FLIP fractions of the blend, and/or 'apic' (not with linear)")
    parser.add_argument("--end-time", default="2")
    parser.add_argument("--only-table", action="store_true", help="collect, do not run")
    parser.add_argument("--example", default=EXAMPLE, help="the example_04 executable")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    compositions = list(itertools.product(
        args.shapes.split(","), args.schemes.split(","), [float(c) for c in args.cells.split(",")],
        [int(p) for p in args.ppcs.split(",")], args.flips.split(",")))
    rows = []
    for i, (shape, scheme, cell, ppc, flip) in enumerate(compositions):
        if flip == "apic" and shape == "linear":
            continue  # APIC needs a kernel with a continuous gradient
        name = tag(shape, scheme, cell, ppc, flip, args.floor)
        out = os.path.join(args.out, name)
        summary = os.path.join(out, "summary.txt")
        if not os.path.exists(summary) and not args.only_table:
            command = [args.example, "--shape", shape, "--scheme", scheme, "--cell", repr(cell),
                       "--ppc", str(ppc), "--floor", args.floor, "--allow-fragile", "true",
                       "--end-time", args.end_time, "--frames", "false", "--threads", "1",
                       "--out", out]
            command += ["--transfer", "apic"] if flip == "apic" else ["--flip", flip]
            started = time.time()
            print(f"[{i + 1}/{len(compositions)}] {name}", file=sys.stderr, flush=True)
            os.makedirs(out, exist_ok=True)
            with open(os.path.join(out, "log.txt"), "w") as log:
                subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=env, check=False)
            print(f"    {time.time() - started:.0f} s", file=sys.stderr, flush=True)
        if not os.path.exists(summary):
            continue
        values = read_summary(summary)
        values["tag"] = name
        rows.append(values)

    columns = ["tag", "shape", "scheme", "cell_m", "ppc", "transfer", "flip", "floor", "status", "time_s",
               "rest_time_s", "steps", "particles", "wall_seconds", "deposit_front_m",
               "extreme_front_m", "tail_mass_fraction", "height_at_wall_m", "max_volume_ratio",
               "grid_kinetic_J_per_m", "particle_kinetic_J_per_m", "energy_scale_J_per_m",
               "reference_runout_power_m", "reference_final_height_m", "error"]
    with open(os.path.join(args.out, "matrix.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)

    def number(text, scale=1.0, digits=3):
        try:
            value = float(text)
        except (TypeError, ValueError):
            return "-"
        return "-" if value != value else f"{value * scale:.{digits}f}"

    lines = ["| shape | scheme | cell mm | ppc | FLIP | outcome | t s | runout m | runout vs exp. "
             "| extreme front m | tail mass % | h(wall) m | max V/V0 | run s |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        outcome = r.get("status", "?")
        if outcome == "stopped":
            message = r.get("error", "")
            outcome = "stopped: " + ("det F <= 0" if "volume ratio" in message else
                                     "left the grid" if "left the grid" in message else
                                     "non-finite" if "not finite" in message else message[:40])
        reference = float(r.get("reference_runout_power_m", "nan"))
        try:
            versus = f"{100 * (float(r['deposit_front_m']) / reference - 1):+.1f} %"
            if versus == "+nan %":
                versus = "-"
        except (KeyError, ValueError):
            versus = "-"
        lines.append("| " + " | ".join([
            r.get("shape", ""), r.get("scheme", ""), number(r.get("cell_m"), 1e3, 1),
            r.get("ppc", ""), "APIC" if r.get("transfer") == "apic" else r.get("flip", ""), outcome, number(r.get("time_s"), 1, 3),
            number(r.get("deposit_front_m")), versus, number(r.get("extreme_front_m")),
            number(r.get("tail_mass_fraction"), 100, 2), number(r.get("height_at_wall_m"), 1, 4),
            number(r.get("max_volume_ratio"), 1, 1), number(r.get("wall_seconds"), 1, 0)]) + " |")
    with open(os.path.join(args.out, "matrix.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{len(rows)} of {len(compositions)} compositions in {args.out}/matrix.csv and "
          f"matrix.md", file=sys.stderr)


if __name__ == "__main__":
    main()
