#!/usr/bin/python3
"""Plot the output of example_06_flat_blade_3d (one run directory, or several to compare).

usage: /usr/bin/python3 scripts/plot_flat_blade_3d.py RUN_DIR [RUN_DIR ...] [--out PNG]
                                                     [--sweep PNG] [--table]

One PNG (default: RUN_DIR/flat_blade_3d.png of the first run), four panels:
  draft per metre of width against travel, with each depth's Sokolovski value;
  the blade's normal force per metre of width across the rig at --profile-at (y / half-width:
  0 the symmetry plane, 1 the glass);
  the free surface at the end, at mid-width and next to the glass;
  the normal stress on the blade against depth, at mid-width and at the glass.

--sweep PNG adds a second figure from the same runs, grouped by depth: the draft as a multiple
of Sokolovski's against the glass friction angle (glass 0: the frictionless walls, e.g. a
one-cell slab) beside the experiment derived from the paper's percentages (plot_paper.py),
and the draft the glass adds, as a fraction of the frictionless draft, against
tan(glass angle), with the gap to the experiment each depth would need closed.
--table prints the runs as a Markdown table (docs/validation.md): drafts against the
frictionless run of the same depth, Sokolovski and the experiment; the blade's normal force at
mid-width and in the column on the glass; the heave's peak at mid-width and at the glass and
the largest difference between those two surface profiles ahead of the blade.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from plot_flat_blade import read_csv  # noqa: E402
from plot_paper import PAPER_DEPTHS, PAPER_MPM_BELOW_EXPERIMENT, PAPER_MPM_OVER_SOKOLOVSKI  # noqa: E402


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
    parser.add_argument("--sweep", type=pathlib.Path)
    parser.add_argument("--table", action="store_true")
    args = parser.parse_args()
    if args.sweep:
        plot_sweep(args.runs, args.sweep)
    if args.table:
        print_table(args.runs)
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
        for (x, z), style, where in zip(surface_profiles(run, summary), ("-", ":"),
                                        ("mid-width", "at the glass")):
            surface.plot(x, z * 1e3, colour + style,
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
                title="Free surface at the end of travel (solid: mid-width; dotted: glass)")
    stress.set(xlabel="normal stress on the blade [kPa]", ylabel="depth [mm]",
               title="Blade normal stress at --profile-at")
    stress.invert_yaxis()
    for axis in axes.flat:
        axis.grid(alpha=0.3)
        if axis.get_legend_handles_labels()[1]:
            axis.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("plot_flat_blade_3d: wrote", out)


def surface_profiles(run, summary):
    """The free surface (x, z) ahead of the blade at mid-width and next to the glass."""
    top = read_csv(run / "surface.csv")
    # Ahead of the blade's face only (behind it: grains the fixed floor kept under it).
    face = summary.get("blade_face_end_m", 0.06 + summary["travel_reached_m"])
    ahead = top["x_m"] > face
    top = {name: values[ahead] for name, values in top.items()}
    ys = np.unique(top["y_m"])
    profiles = []
    for y in (ys[0], ys[-1]):
        pick = top["y_m"] == y
        order = np.argsort(top["x_m"][pick])
        profiles.append((top["x_m"][pick][order], top["z_top_m"][pick][order]))
    return profiles


def print_table(runs):
    summaries = [(run, read_summary(run)) for run in runs]
    frictionless = {s["depth_m"]: s["draft_N_per_m"] for _, s in summaries
                    if s["glass_friction_deg"] == 0.0}
    print("| h [mm] | glass [deg] | draft [N/m] | rig [N] | vertical [N/m] | against glass 0 "
          "| against Sokolovski | against the experiment | blade force mid-width / glass "
          "column [N/m] | heave peak mid-width / glass [mm] | surfaces differ by [mm] |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")

    def percent(value, reference):
        return "%+.1f %%" % (100 * (value / reference - 1)) if reference else "-"

    for run, s in sorted(summaries, key=lambda r: (r[1]["depth_m"], r[1]["glass_friction_deg"])):
        depth, draft = s["depth_m"], s["draft_N_per_m"]
        across = read_csv(run / "width_profile.csv")
        (x_mid, z_mid), (x_glass, z_glass) = surface_profiles(run, s)
        common = np.intersect1d(x_mid, x_glass)
        difference = (z_glass[np.isin(x_glass, common)] - z_mid[np.isin(x_mid, common)]) * 1e3
        print("| %.0f | %g | %.1f | %.1f | %.1f | %s | %s | %s | %.0f / %.0f | %.1f / %.1f "
              "| %+.1f to %+.1f |" % (
                  depth * 1e3, s["glass_friction_deg"], draft, s["draft_N_rig"],
                  s["vertical_N_per_m"], percent(draft, frictionless.get(depth)),
                  percent(draft, s["sokolovski_N_per_m"]),
                  percent(draft, experiment_draft(depth, s["sokolovski_N_per_m"])),
                  across["normal_force_N_per_m"][0], across["normal_force_N_per_m"][-1],
                  z_mid.max() * 1e3, z_glass.max() * 1e3, difference.min(), difference.max()))


def experiment_draft(depth, sokolovski):
    """The measured draft the paper's percentages imply (docs/validation.md), or None."""
    for k, paper_depth in enumerate(PAPER_DEPTHS):
        if abs(depth - paper_depth) < 1e-9:
            return PAPER_MPM_OVER_SOKOLOVSKI[k] * sokolovski / (1 - PAPER_MPM_BELOW_EXPERIMENT[k])
    return None


def plot_sweep(runs, out):
    by_depth = {}
    for run in runs:
        summary = read_summary(run)
        by_depth.setdefault(summary["depth_m"], []).append(summary)
    fig, (drafts, added) = plt.subplots(1, 2, figsize=(12, 4.8))
    for k, depth in enumerate(sorted(by_depth)):
        colour = "C%d" % k
        series = sorted(by_depth[depth], key=lambda s: s["glass_friction_deg"])
        angles = np.array([s["glass_friction_deg"] for s in series])
        values = np.array([s["draft_N_per_m"] for s in series])
        name = "h = %.0f mm" % (depth * 1e3)
        sokolovski = series[0]["sokolovski_N_per_m"]
        drafts.plot(angles, values / sokolovski, colour + "o-", label=name)
        experiment = experiment_draft(depth, sokolovski)
        if experiment is not None:
            drafts.axhline(experiment / sokolovski, color=colour, ls=":", lw=1.2)
        if angles[0] != 0.0:
            continue
        frictionless = values[0]
        added.plot(np.tan(np.radians(angles)), 100 * (values / frictionless - 1), colour + "o-",
                   label=name)
        if experiment is not None:
            added.axhline(100 * (experiment / frictionless - 1), color=colour, ls=":", lw=1.2)
    drafts.axhline(1.0, color="k", ls="--", lw=0.8)
    drafts.set(xlabel="glass friction angle [deg]", ylabel="draft / Sokolovski's",
               title="Draft (dashed: Sokolovski; dotted: experiment from the paper's %)")
    added.set(xlabel="tan(glass friction angle)", ylabel="draft added by the glass [%]",
              title="Added draft (dotted: what the experiment needs)")
    for axis in (drafts, added):
        axis.grid(alpha=0.3)
        axis.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("plot_flat_blade_3d: wrote", out)


if __name__ == "__main__":
    main()
