#!/usr/bin/python3
"""Plot the output of example_05_strip_footing: footing pressure / c against settlement / B
for each mesh, without (dashed) and with (solid) F-bar anti-locking, beside Prandtl's
collapse pressure (2 + pi) c; a second panel shows the limit pressure of each run against
the cell size. A second PNG shows the mechanism at the end of the finest mesh's runs (the
particles coloured by their plastic shear strain) beside Prandtl's slip lines.

usage: /usr/bin/python3 scripts/plot_strip_footing.py [DIR ...] [--output PNG]
DIR defaults to strip_footing; several DIRs (runs of different meshes) are drawn together. The
PNGs default to the first DIR's strip_footing.png and strip_footing_mechanism.png (beside
--output when it is given).
"""
import argparse
import csv
import math
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRANDTL = 2.0 + math.pi


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
    parser.add_argument("directories", nargs="*", default=["strip_footing"])
    parser.add_argument("--output", default=None, help="PNG file (default DIR/strip_footing.png)")
    args = parser.parse_args()
    directories = [pathlib.Path(d) for d in args.directories]
    curves, summary = [], {}
    for directory in directories:
        summary_path = directory / "summary.csv"
        found = list(directory.glob("curve_n*_*.csv"))
        if not found or not summary_path.exists():
            sys.exit(f"error: no curve_n*_*.csv / summary.csv in '{directory}'; "
                     "run example_05_strip_footing --out DIR first")
        curves += found
        for key, values in read_csv(summary_path).items():
            summary.setdefault(key, []).extend(values)
    curves.sort(key=lambda p: (int(re.search(r"_n(\d+)_", p.name).group(1)), p.name))
    directory = directories[0]

    meshes = sorted({int(re.search(r"_n(\d+)_", p.name).group(1)) for p in curves})
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    colour_of = {n: colours[i % len(colours)] for i, n in enumerate(meshes)}
    fig, (ax_curve, ax_limit) = plt.subplots(1, 2, figsize=(13, 5.2),
                                             gridspec_kw={"width_ratios": [1.6, 1]})
    top = PRANDTL
    for path in curves:
        n = int(re.search(r"_n(\d+)_", path.name).group(1))
        fbar = path.stem.endswith("fbar")
        curve = read_csv(path)
        top = max(top, max(curve["pressure_over_c"]))
        ax_curve.plot(curve["settlement_over_B"], curve["pressure_over_c"], color=colour_of[n],
                      linestyle="-" if fbar else "--", linewidth=1.8 if fbar else 1.3,
                      label=f"b/h = {n}, {'F-bar' if fbar else 'no anti-locking'}")
    ax_curve.axhline(PRANDTL, color="black", linewidth=1.2, linestyle=":",
                     label=f"Prandtl (2 + $\\pi$) c = {PRANDTL:.3f} c")
    ax_curve.set_xlabel("settlement / B")
    ax_curve.set_ylabel("footing pressure q / c")
    ax_curve.set_ylim(0, 1.05 * top)
    ax_curve.set_xlim(left=0)
    ax_curve.grid(alpha=0.3)
    ax_curve.legend(fontsize=8, ncol=2, loc="lower right")
    ax_curve.set_title("Strip footing on a weightless Tresca layer (nu = 0.49)")

    for fbar, marker, name in ((0.0, "s", "no anti-locking"), (1.0, "o", "F-bar")):
        points = [(h, q) for h, f, q in zip(summary["h_over_B"], summary["fbar"],
                                            summary["limit_pressure_over_c"]) if f == fbar]
        if points:
            points.sort()
            ax_limit.plot([p[0] for p in points], [p[1] for p in points], marker=marker,
                          color="black", linestyle="-" if fbar else "--", label=name)
    ax_limit.axhline(PRANDTL, color="black", linewidth=1.2, linestyle=":", label="(2 + $\\pi$) c")
    ax_limit.axhspan(0.95 * PRANDTL, 1.05 * PRANDTL, color="grey", alpha=0.2, label="$\\pm$ 5 %")
    ax_limit.set_xscale("log")
    ax_limit.set_xlabel("cell size h / B")
    ax_limit.set_ylabel("limit pressure q_u / c (mean over the plateau)")
    ax_limit.grid(alpha=0.3, which="both")
    ax_limit.legend(fontsize=8)
    ax_limit.set_title("Limit pressure against cell size")
    fig.tight_layout()
    output = pathlib.Path(args.output) if args.output else directory / "strip_footing.png"
    fig.savefig(output, dpi=110)
    print(f"wrote {output}")
    finest = [d for d in directories if list(d.glob(f"particles_n{meshes[-1]}_*.csv"))]
    if finest:
        plot_mechanism(finest[0], meshes[-1], output.with_name(output.stem + "_mechanism.png"))


def prandtl_lines(b, top):
    """Prandtl's mechanism of a smooth footing of half-width b for phi = 0, the half x >= 0 of
    the surface y = top: the active wedge's boundary from the axis at depth b to the footing's
    edge, the fan about the edge (radius b sqrt 2) from there to (2 b, top - b), the boundary
    of the passive wedge, and the passive wedge's slip line reaching the surface at 3 b."""
    r = b * math.sqrt(2.0)
    angles = [-0.75 * math.pi + k * (0.5 * math.pi) / 40 for k in range(41)]
    return [([0.0, b], [top - b, top]),
            ([b + r * math.cos(t) for t in angles], [top + r * math.sin(t) for t in angles]),
            ([b, 2 * b], [top, top - b]),
            ([2 * b, 3 * b], [top - b, top])]


def plot_mechanism(directory, mesh, output):
    paths = [directory / f"particles_n{mesh}_{policy}.csv" for policy in ("none", "fbar")]
    paths = [p for p in paths if p.exists()]
    if not paths:
        return
    fig, axes = plt.subplots(1, len(paths), figsize=(6.2 * len(paths), 4.2), squeeze=False)
    for ax, path in zip(axes[0], paths):
        particles = read_csv(path)
        x, y = particles["x_m"], particles["y_m"]
        top = max(yy - uy for yy, uy in zip(y, particles["uy_m"]))  # the surface at the start
        settlement = max(-uy for uy in particles["uy_m"])  # the wedge under the footing
        b = 0.5  # the footing's half-width at the example's default B = 1 m
        shown = ax.scatter(x, y, c=particles["plastic_shear_strain"], s=1.6 if len(x) > 20000
                           else 2.5, vmin=0, vmax=0.3, cmap="viridis", linewidths=0)
        for k, (lx, ly) in enumerate(prandtl_lines(b, top)):
            ax.plot(lx, ly, color="red", linewidth=1.0, linestyle="--", zorder=3,
                    label="Prandtl's mechanism (at the start)" if k == 0 else None)
        ax.plot([0, b], [top - settlement] * 2, color="black", linewidth=3, zorder=3,
                label="footing")
        ax.set_xlim(0, 4 * b)
        ax.set_ylim(top - 2.2 * b, top + 0.3 * b)
        ax.set_aspect("equal")
        policy = "F-bar" if path.stem.endswith("fbar") else "no anti-locking"
        ax.set_title(f"b/h = {mesh}, {policy}: plastic shear strain at the end", fontsize=10)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.legend(fontsize=7, loc="lower right")
        fig.colorbar(shown, ax=ax, shrink=0.8)
    fig.tight_layout()
    fig.savefig(output, dpi=100)
    try:  # a palette PNG: a third of the size, the same picture
        from PIL import Image
        Image.open(output).convert("RGB").quantize(colors=256).save(output, optimize=True)
    except ImportError:
        pass
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
