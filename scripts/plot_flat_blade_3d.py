#!/usr/bin/python3
"""Plot the output of example_06_flat_blade_3d (one run directory, or several to compare).

usage: /usr/bin/python3 scripts/plot_flat_blade_3d.py RUN_DIR [RUN_DIR ...] [--out PNG]

One PNG (default: RUN_DIR/flat_blade_3d.png of the first run), four panels:
  draft per metre of width against travel, with each depth's Sokolovski value;
  the blade's normal force per metre of width across the rig at --profile-at (y / half-width:
  0 the symmetry plane, 1 the glass);
  the free surface at the end, at mid-width and next to the glass;
  the normal stress on the blade against depth, at mid-width and at the glass.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from plot_flat_blade import read_csv  # noqa: E402


def read_summary(run):
    values = {}
    for line in (run / "summary.txt").read_text().splitlines():
        if "=" in line:
            name, value = line.split("=", 1)
            values[name.strip()] = float(value)
    return values


def label_of(summary):
    return "h = %.0f mm, glass %.0f deg, width %.0f mm" % (
        summary["depth_m"] * 1e3, summary["glass_friction_deg"], summary["width_m"] * 1e3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", type=pathlib.Path)
    parser.add_argument("--out", type=pathlib.Path)
    args = parser.parse_args()
    out = args.out or args.runs[0] / "flat_blade_3d.png"
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    drafts, across, surface, stress = axes.flat
    sokolovski_done = set()
    for k, run in enumerate(args.runs):
        colour = "C%d" % k
        summary = read_summary(run)
        label = label_of(summary)
        forces = read_csv(run / "forces.csv")
        drafts.plot(forces["travel_m"] * 1e3, forces["draft_N_per_m"], colour, lw=0.8,
                    label="%s: %.0f N/m" % (label, summary["draft_N_per_m"]))
        depth = summary["depth_m"]
        if depth not in sokolovski_done:
            sokolovski_done.add(depth)
            drafts.axhline(summary["sokolovski_N_per_m"], color="k", ls="--", lw=0.8)
            drafts.annotate("Sokolovski, h = %.0f mm" % (depth * 1e3),
                            (0.5, summary["sokolovski_N_per_m"]), fontsize=8,
                            textcoords="offset points", xytext=(0, 3))
        half = summary["modelled_width_m"]
        width_profile = read_csv(run / "width_profile.csv")
        across.plot(width_profile["y_m"] / half, width_profile["normal_force_N_per_m"], colour + "o-",
                    label=label)
        top = read_csv(run / "surface.csv")
        # Ahead of the blade's face only (behind it: grains the fixed floor kept under it).
        face = summary.get("blade_face_end_m", 0.06 + summary["travel_reached_m"])
        ahead = top["x_m"] > face
        top = {name: values[ahead] for name, values in top.items()}
        ys = np.unique(top["y_m"])
        for y, style, where in ((ys[0], "-", "mid-width"), (ys[-1], ":", "at the glass")):
            pick = top["y_m"] == y
            order = np.argsort(top["x_m"][pick])
            surface.plot(top["x_m"][pick][order], top["z_top_m"][pick][order] * 1e3, colour + style,
                         label="%s, %s" % (label, where) if len(args.runs) < 4 else None)
        traction = read_csv(run / "blade_traction.csv")
        columns = np.unique(traction["y_m"])
        for y, style, where in ((columns[0], "-", "mid-width"), (columns[-1], ":", "glass")):
            pick = (traction["y_m"] == y) & (traction["depth_m"] >= 0.0)
            stress.plot(traction["normal_traction_Pa"][pick] / 1e3, traction["depth_m"][pick] * 1e3,
                        colour + style, label="%s, %s" % (label, where))
    drafts.set(xlabel="blade travel [mm]", ylabel="draft per metre of width [N/m]",
               title="Draft (legend: average over the run's window, 15-35 mm by default)")
    across.set(xlabel="y / modelled width (0: symmetry plane, 1: glass)",
               ylabel="normal force on the blade [N/m]", title="Blade force across the rig")
    surface.set(xlabel="x [m]", ylabel="free surface [mm]",
                title="Free surface at the end of travel")
    stress.set(xlabel="normal stress on the blade [kPa]", ylabel="depth [mm]",
               title="Blade normal stress at --profile-at")
    stress.invert_yaxis()
    for axis in axes.flat:
        axis.grid(alpha=0.3)
        axis.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("plot_flat_blade_3d: wrote", out)


if __name__ == "__main__":
    main()
