#!/usr/bin/python3
"""Collect the summary.csv of every flat-blade run under DIR into a Markdown table.

usage: /usr/bin/python3 scripts/validation_table.py [DIR]   (default out/flat_blade)
"""
import csv
import pathlib
import sys


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out/flat_blade")
    rows = []
    for path in sorted(root.glob("*/summary.csv")):
        with open(path, newline="") as handle:
            row = next(csv.DictReader(handle))
        row["run"] = path.parent.name
        # The early draft, before the soil heaves up in front of the blade (5-10 mm).
        with open(path.parent / "forces.csv", newline="") as handle:
            forces = [r for r in csv.DictReader(handle)
                      if 0.005 <= float(r["displacement_m"]) <= 0.010]
        row["early"] = (sum(float(r["draft_N_per_m"]) for r in forces) / len(forces)
                        if forces else float("nan"))
        rows.append(row)
    rows.sort(key=lambda r: (float(r["polar"]), -float(r["cells_x"]), float(r["depth_m"])))
    print("| h [mm] | mesh | continuum | draft 15-35 mm [N/m] | Sokolovski [N/m] | "
          "difference | draft 5-10 mm [N/m] | vertical 15-35 mm [N/m] | particles | steps | "
          "run time [s] |")
    print("| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        soko = float(r["sokolovski_draft_N_per_m"])
        print("| %.0f | %sx%s | %s | %.1f | %.1f | %+.1f %% | %.1f (%+.1f %%) | %.1f | %s | %s | %.0f |"
              % (float(r["depth_m"]) * 1000, r["cells_x"], r["cells_y"],
                 "polar" if float(r["polar"]) > 0.5 else "nonpolar",
                 float(r["average_draft_N_per_m"]), soko, float(r["difference_percent"]),
                 r["early"], 100.0 * (r["early"] - soko) / soko,
                 float(r["average_vertical_N_per_m"]), r["particles"], r["steps"],
                 float(r["run_seconds"])))


if __name__ == "__main__":
    main()
