#!/usr/bin/python3
"""Plot the output of example_02_earth_pressure: blade normal and shear stress against depth
and the slip lines, one colour per blade depth.

usage: /usr/bin/python3 scripts/plot_earth_pressure.py [DIR] [--output PNG]
DIR defaults to out/earth_pressure; the PNG defaults to DIR/earth_pressure.png.
Stresses are shown compression positive (soil on blade), shear upward on the blade.
"""
import argparse
import csv
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        columns = [[] for _ in header]
        for row in reader:
            for column, value in zip(columns, row):
                column.append(float(value))
    return dict(zip(header, columns))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory", nargs="?", default="out/earth_pressure")
    parser.add_argument("--output", default=None, help="PNG file (default DIR/earth_pressure.png)")
    args = parser.parse_args()
    directory = pathlib.Path(args.directory)
    walls = sorted(directory.glob("wall_h*.csv"),
                   key=lambda p: int(re.search(r"h(\d+)", p.stem).group(1)))
    summary_path = directory / "summary.csv"
    if not walls or not summary_path.exists():
        sys.exit(f"error: no wall_h*.csv / summary.csv in '{directory}'; "
                 "run example_02_earth_pressure --out DIR first")
    summary = read_csv(summary_path)

    fig, (ax_stress, ax_slip) = plt.subplots(1, 2, figsize=(12, 5.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for index, wall_path in enumerate(walls):
        tag = re.search(r"h(\d+)", wall_path.stem).group(1)
        colour = colours[index % len(colours)]
        wall = read_csv(wall_path)
        depth_mm = [1e3 * z for z in wall["depth_m"]]
        # The gamma-only profiles coincide where they overlap: deeper ones drawn wider, below.
        width = 1.2 + 1.2 * index
        order = len(walls) - index
        ax_stress.plot([1e-3 * s for s in wall["normal_pressure_Pa_compression_positive"]],
                       depth_mm, color=colour, linewidth=width, zorder=order,
                       label=f"normal, h = {tag} mm")
        ax_stress.plot([1e-3 * s for s in wall["shear_stress_Pa_on_wall_upward"]], depth_mm,
                       color=colour, linestyle="--", linewidth=width, zorder=order,
                       label=f"shear, h = {tag} mm")

        slip = read_csv(directory / f"slip_line_h{tag}.csv")
        ax_slip.plot([1e3 * x for x in slip["distance_from_wall_m"]],
                     [1e3 * z for z in slip["depth_m"]], color=colour,
                     label=f"Sokolovski, h = {tag} mm")
        row = min(range(len(summary["height_m"])),
                  key=lambda i: abs(1e3 * summary["height_m"][i] - int(tag)))
        height_mm = 1e3 * summary["height_m"][row]
        ax_slip.plot([0, 1e3 * summary["rankine_exit_m"][row]], [height_mm, 0], color=colour,
                     linestyle=":", linewidth=1)
        ax_slip.plot([0, 1e3 * summary["coulomb_exit_m"][row]], [height_mm, 0], color=colour,
                     linestyle="-.", linewidth=1)
        ax_slip.plot([0, 0], [0, height_mm], color="black", linewidth=3)

    ax_stress.set_xlabel("stress on the blade [kPa] (normal: compression positive; shear: upward)")
    ax_stress.set_ylabel("depth below the surface [mm]")
    ax_stress.invert_yaxis()
    ax_stress.set_xlim(left=0)
    ax_stress.grid(True, alpha=0.3)
    ax_stress.legend(fontsize=8)
    ax_stress.set_title("Blade stresses (method of characteristics)")

    ax_slip.plot([], [], color="grey", linestyle=":", label="Rankine plane")
    ax_slip.plot([], [], color="grey", linestyle="-.", label="Coulomb plane")
    ax_slip.set_xlabel("distance from the blade [mm]")
    ax_slip.set_ylabel("depth below the surface [mm]")
    ax_slip.invert_yaxis()
    ax_slip.set_aspect("equal")
    ax_slip.grid(True, alpha=0.3)
    ax_slip.legend(fontsize=8, loc="lower right")
    ax_slip.set_title("Slip line from the blade tip")

    fig.tight_layout()
    output = pathlib.Path(args.output) if args.output else directory / "earth_pressure.png"
    fig.savefig(output, dpi=120)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
