#!/usr/bin/python3
"""Tables of the polar flat-blade studies (scripts/polar_studies.sh): drafts and blade shear
over 15-35 mm at h = 150, 250, 350 mm, each study against its reference, and the band.

usage: /usr/bin/python3 scripts/polar_studies_table.py OUT_DIR [--figure PNG] > OUT_DIR/studies.md

A run that did not complete shows as "stopped" (its log says why). --figure draws the band of
the mesh-orientation study at h = 250 mm and 15 mm of travel, in the rig's axes: the Cosserat
rotation (polar) and the shear-strain intensity since the blade started (nonpolar), each on
the grid along the rig and turned 35 deg against it.
"""
import csv
import pathlib
import sys

import numpy as np

from plot_flat_blade import in_rig_axes, read_frame  # same folder
from shear_band_width import frame_at, measure, summary_of

DEPTHS = ("0.15", "0.25", "0.35")
# (name, what it is, the run it is compared with)
STUDIES = (
    ("mc", "nonpolar Mohr-Coulomb", None),
    ("dp", "nonpolar Drucker-Prager, polar run's cone (per angle)", "mc"),
    ("dp_ps", "nonpolar Drucker-Prager, exact plane-strain cone", "mc"),
    ("held", "polar, rotation held at the blade (the paper's)", "mc"),
    ("held", "polar, held: the Cosserat effect alone (same cone)", "dp"),
    ("free", "polar, rotation free at the blade", "held"),
    ("coupled", "polar, Cosserat wall friction at the blade", "held"),
    ("gc05", "polar, Gc = 0.5 G (the paper: -1.3 %)", "held"),
    ("l2", "polar, l = 2 mm (the paper: -1.9 %)", "held"),
    ("ps", "polar, exact plane-strain cone", "held"),
    ("ps", "polar, exact cone: the Cosserat effect alone", "dp_ps"),
    ("held_d7", "polar, blade friction delta = 7 deg (about half the friction)", "mc"),
    ("held_d0", "polar, frictionless blade", "mc"),
    ("rot35_mc", "nonpolar Mohr-Coulomb, rig turned 35 deg", "mc"),
    ("rot35_held", "polar, held, rig turned 35 deg", "held"),
    ("rot35_free", "polar, free at the blade, rig turned 35 deg", "free"),
)


def summary(runs, name):
    path = runs / name / "summary.csv"
    if not path.exists():
        return None
    with open(path, newline="") as handle:
        return {k: float(v) for k, v in next(csv.DictReader(handle)).items()}


def percent(value, reference):
    return "%+.1f %%" % (100.0 * (value - reference) / reference)


def band_figure(runs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = ("held_h0.25", "rot35_held_h0.25", "mc_h0.25", "rot35_mc_h0.25")
    titles = ("polar, grid along the rig", "polar, rig turned 35 deg against the grid",
              "nonpolar, grid along the rig", "nonpolar, rig turned 35 deg against the grid")
    fig, axes = plt.subplots(2, 2, figsize=(12, 4.6), sharex=True, sharey=True)
    for ax, name, title in zip(axes.T.ravel(), names, titles):
        run = runs / name
        if not (run / "summary.csv").exists():
            ax.set_title(title + ": stopped")
            continue
        s = summary_of(run)
        first, path, at = frame_at(run, s["cutting_start_s"], s["blade_speed_m_per_s"], 0.015)
        start, frame = read_frame(first), read_frame(path)
        x = in_rig_axes(s, frame["position"])
        if frame["micro_rotation"] is not None:
            value, label, cmap = -frame["micro_rotation"], "-rotation [rad]", "magma_r"
        else:
            exx = frame["strain_xx"] - start["strain_xx"]
            eyy = frame["strain_yy"] - start["strain_yy"]
            exy = frame["strain_xy"] - start["strain_xy"]
            value = np.sqrt(((exx - eyy) ** 2 + eyy ** 2 + exx ** 2) / 6 + exy ** 2)
            label, cmap = "shear-strain intensity", "magma_r"
        top = np.percentile(value, 99)
        points = ax.scatter(x[:, 0], x[:, 1], c=value, s=1.5, cmap=cmap, vmin=0, vmax=top)
        fig.colorbar(points, ax=ax, label=label, fraction=0.05)
        ax.set_title("%s (%.0f mm)" % (title, at * 1000), fontsize=10)
        ax.set_aspect("equal")
        ax.set_xlim(0.0, 0.7)
        ax.set_ylim(-0.01, 0.3)
    for ax in axes[1]:
        ax.set_xlabel("x along the floor [m]")
    for ax in axes[:, 0]:
        ax.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    args = sys.argv[1:]
    figure = None
    if "--figure" in args:
        at = args.index("--figure")
        figure = pathlib.Path(args[at + 1])
        del args[at:at + 2]
    if len(args) != 1:
        sys.exit(__doc__)
    runs = pathlib.Path(args[0]) / "runs"
    if figure:
        band_figure(runs, figure)
    print("Drafts over 15-35 mm of travel [N/m], each against the run in the last column")
    print("(Sokolovski: 306.7, 852.0, 1669.8 N/m at h = 150, 250, 350 mm).\n")
    print("| study | h = 150 | h = 250 | h = 350 | against |")
    print("| --- | ---: | ---: | ---: | --- |")
    for name, what, reference in STUDIES:
        cells = []
        for depth in DEPTHS:
            s = summary(runs, "%s_h%s" % (name, depth))
            r = summary(runs, "%s_h%s" % (reference, depth)) if reference else None
            if s is None:
                ran = (runs / ("%s_h%s.status" % (name, depth))).exists()
                cells.append("stopped" if ran else "-")
            elif reference is None:
                cells.append("%.1f (%s Sok.)" % (s["average_draft_N_per_m"],
                                                 percent(s["average_draft_N_per_m"],
                                                         s["sokolovski_draft_N_per_m"])))
            elif r is None:
                cells.append("%.1f" % s["average_draft_N_per_m"])
            else:
                cells.append("%.1f (%s)" % (s["average_draft_N_per_m"],
                                            percent(s["average_draft_N_per_m"],
                                                    r["average_draft_N_per_m"])))
        print("| %s: %s | %s | %s |" % (name, what, " | ".join(cells), reference or "Sokolovski"))
    print("\nBlade shear over 15-35 mm: the vertical force over the draft (tan 14 deg = 0.249 when")
    print("friction is fully mobilised along the face), and the largest Cosserat rotation.\n")
    print("| run | h = 150 | h = 250 | h = 350 | largest rotation at 35 mm [rad] |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for name in ("mc", "dp", "held", "free", "coupled", "gc05", "l2", "ps", "held_d7", "held_d0",
                 "rot35_mc", "rot35_held"):
        cells, rotation = [], []
        for depth in DEPTHS:
            s = summary(runs, "%s_h%s" % (name, depth))
            if s is None:
                cells.append("stopped")
                continue
            cells.append("%.3f" % (-s["average_vertical_N_per_m"] / s["average_draft_N_per_m"]))
            rotation.append("%.3f" % s["max_rotation_rad"])
        print("| %s | %s | %s |" % (name, " | ".join(cells), ", ".join(rotation) or "-"))
    print("\nShear band at 15 mm of travel (scripts/shear_band_width.py): inclination to the")
    print("rig's floor and width normal to the band at h/3 and 2h/3.\n")
    print("| run | indicator | inclination [deg] | widths [mm] |")
    print("| --- | --- | ---: | --- |")
    for folder in sorted(p for p in runs.iterdir() if (p / "summary.csv").exists()):
        try:
            indicator, _, theta, widths = measure(folder, 0.015)
        except (ValueError, IndexError) as error:  # a run without frames at 15 mm
            print("| %s | - | - | %s |" % (folder.name, error))
            continue
        print("| %s | %s | %.0f | %.0f, %.0f |" % (folder.name, indicator, theta,
                                                   widths[0] * 1000, widths[1] * 1000))


if __name__ == "__main__":
    main()
