#!/usr/bin/python3
"""Plot the output of example_03_flat_blade (one run directory, or several to compare).

usage: /usr/bin/python3 scripts/plot_flat_blade.py RUN_DIR [RUN_DIR ...] [--output DIR]

Writes into the first RUN_DIR (or --output):
  forces.png        draft and vertical blade force against travel, the 15-35 mm average and
                    Sokolovski's value (the paper's Figs. 6-8)
  blade_stress.png  normal and shear stress on the blade against depth at the profile travel,
                    with Sokolovski's (the paper's Fig. 9); compression positive
  fields.png        at the frame closest to 15 mm of travel: yield points, shear-strain
                    intensity J', particle displacement ratio PDR >= 0.15 and, for polar runs,
                    the Cosserat rotation (the paper's Figs. 11-14), with Sokolovski's slip line
"""
import argparse
import csv
import pathlib
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path, newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        rows = [[float(v) for v in row] for row in reader if row]
    data = np.array(rows) if rows else np.zeros((0, len(header)))
    return {name: data[:, i] for i, name in enumerate(header)}


def label_of(run):
    summary = read_csv(run / "summary.csv")
    polar = summary["polar"][0] > 0.5
    return "%s MPM, h = %.0f mm, %dx%d" % ("polar" if polar else "nonpolar",
                                          summary["depth_m"][0] * 1000,
                                          summary["cells_x"][0], summary["cells_y"][0])


def plot_forces(runs, output):
    fig, ax = plt.subplots(figsize=(8, 5))
    for run in runs:
        forces = read_csv(run / "forces.csv")
        summary = read_csv(run / "summary.csv")
        width = summary["rig_width_m"][0]
        line, = ax.plot(forces["displacement_m"] * 1000, forces["draft_N_rig"],
                        label="draft, " + label_of(run))
        ax.plot(forces["displacement_m"] * 1000, forces["vertical_N_rig"], "--",
                color=line.get_color(), label="vertical, " + label_of(run))
        lo, hi = summary["average_from_m"][0] * 1000, summary["average_to_m"][0] * 1000
        ax.hlines(summary["average_draft_N_per_m"][0] * width, lo, hi, colors=line.get_color(),
                  linewidth=3, alpha=0.6)
        ax.axhline(summary["sokolovski_draft_N_per_m"][0] * width, color=line.get_color(),
                   linestyle=":", label="Sokolovski draft, h = %.0f mm"
                   % (summary["depth_m"][0] * 1000))
    first = read_csv(runs[0] / "summary.csv")
    ax.axvspan(first["average_from_m"][0] * 1000, first["average_to_m"][0] * 1000,
               color="0.9", zorder=0, label="averaging window")
    ax.set_xlabel("blade displacement [mm]")
    ax.set_ylabel("force on the %.0f mm wide rig [N]" % (first["rig_width_m"][0] * 1000))
    ax.set_title("Flat blade: force the blade applies (draft +x, vertical +y)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(output / "forces.png", dpi=130)
    plt.close(fig)


def plot_blade_stress(runs, output):
    fig, axes = plt.subplots(1, 2, figsize=(9, 5), sharey=True)
    for run in runs:
        profile_path = run / "blade_stress.csv"
        if not profile_path.exists():
            continue
        profile = read_csv(profile_path)
        keep = (profile["depth_m"] >= -1e-9) & (profile["nodes"] > 0)
        depth = profile["depth_m"][keep] * 1000
        axes[0].plot(profile["normal_traction_Pa"][keep] / 1000, depth, "o-", ms=3,
                     label=label_of(run))
        axes[1].plot(profile["shear_traction_Pa"][keep] / 1000, depth, "o-", ms=3,
                     label=label_of(run))
        wall = read_csv(run / "sokolovski_wall.csv")
        axes[0].plot(wall["normal_pressure_Pa"] / 1000, wall["depth_m"] * 1000, "k--",
                     label="Sokolovski")
        axes[1].plot(wall["shear_stress_Pa"] / 1000, wall["depth_m"] * 1000, "k--",
                     label="Sokolovski")
    summary = read_csv(runs[0] / "summary.csv")
    for ax, title in zip(axes, ["normal stress on the blade [kPa] (compression +)",
                                "shear stress on the blade [kPa] (soil on blade, upward +)"]):
        ax.set_xlabel(title)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("depth below the initial surface [mm]")
    axes[0].invert_yaxis()
    axes[0].legend(fontsize=7)
    fig.suptitle("Blade stresses at %.0f mm of travel" % (summary["profile_at_m"][0] * 1000))
    fig.tight_layout()
    fig.savefig(output / "blade_stress.png", dpi=130)
    plt.close(fig)


def read_frame(path):
    """The fields of one frame the plots use, from frame format version 2 (cosmpm >= 0.1.0:
    /particles/..., N x 3 vectors, N x 9 tensors) or 1 (fields at the root, N x 2 vectors,
    strain [xx, yy, zz, xy(, yx, ...)]): time, position (N x 2), strain_xx, strain_yy,
    strain_xy (the symmetric part of the shear), plastic and micro_rotation (or None)."""
    import h5py

    with h5py.File(path, "r") as h5:
        version = int(h5.attrs.get("version", 1))
        if version == 2:
            group = h5["particles"]
            strain = group["strain"][()]
            frame = {"position": group["position"][()][:, :2],
                     "strain_xx": strain[:, 0], "strain_yy": strain[:, 4],
                     "strain_xy": 0.5 * (strain[:, 1] + strain[:, 3])}
        elif version == 1:
            group = h5
            strain = group["strain"][()]
            shear = strain[:, 3] if strain.shape[1] == 4 else 0.5 * (strain[:, 3] + strain[:, 4])
            frame = {"position": group["position"][()],
                     "strain_xx": strain[:, 0], "strain_yy": strain[:, 1], "strain_xy": shear}
        else:
            raise SystemExit("%s: frame format version %d is newer than this script reads (1, 2)"
                             % (path, version))
        count = len(frame["position"])
        frame["time"] = float(h5.attrs["time"])
        frame["plastic"] = group["plastic"][()] if "plastic" in group else np.zeros(count)
        frame["micro_rotation"] = (group["micro_rotation"][()] if "micro_rotation" in group
                                   else None)
    return frame


def nearest_frame(frames, start, speed, travel):
    """The frame whose blade travel (m since cutting started) is nearest `travel`, and its travel."""
    import h5py

    best, best_travel = None, None
    for path in frames:
        with h5py.File(path, "r") as h5:
            t = (h5.attrs["time"] - start) * speed
        if best is None or abs(t - travel) < abs(best_travel - travel):
            best, best_travel = path, t
    return best, best_travel


def in_rig_axes(summary, position):
    """Positions in the rig's axes (x along the floor, y up from it) for a run whose rig was
    turned against the grid (--rig-angle); unchanged otherwise. `summary`: summary.csv's
    values (numbers or one-element arrays)."""
    def value(name):
        v = summary.get(name, 0.0)
        return float(np.ravel(v)[0])

    angle = np.radians(value("rig_angle_deg"))
    if angle == 0.0:
        return position
    r = position - np.array([value("rig_origin_x_m"), value("rig_origin_y_m")])
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack((c * r[:, 0] + s * r[:, 1], -s * r[:, 0] + c * r[:, 1]))


def plot_fields(run, output):
    frames = sorted((run / "frames").glob("flat_blade_*.h5"))
    if len(frames) < 2:
        return
    summary = read_csv(run / "summary.csv")
    start, speed = summary["cutting_start_s"][0], summary["blade_speed_m_per_s"][0]
    target = 0.015
    first = read_frame(frames[0])
    position0 = in_rig_axes(summary, first["position"])
    best, best_travel = nearest_frame(frames, start, speed, target)
    frame = read_frame(best)
    x = in_rig_axes(summary, frame["position"])
    plastic, rotation = frame["plastic"], frame["micro_rotation"]
    # Strain since the blade started (the first frame is at its start).
    exx = frame["strain_xx"] - first["strain_xx"]
    eyy = frame["strain_yy"] - first["strain_yy"]
    exy = frame["strain_xy"] - first["strain_xy"]
    j2 = ((exx - eyy) ** 2 + eyy ** 2 + exx ** 2) / 6.0 + exy ** 2  # the paper's J'
    pdr = np.linalg.norm(x - position0, axis=1) / max(best_travel, 1e-12)
    face = summary["blade_face_x_m"][0] + best_travel
    depth = summary["depth_m"][0]
    slip = read_csv(run / "sokolovski_slip_line.csv")
    panels = [("yield points (plastic in the last step)", plastic, "viridis", (0, 1)),
              ("shear strain intensity J' since the blade started", j2, "magma",
               (0, np.percentile(j2, 99))),
              ("particle displacement ratio PDR >= 0.15", (pdr >= 0.15).astype(float), "Greys",
               (0, 1.5))]
    if rotation is not None:
        # The 99th percentile: a few particles at the blade tip would wash out the band.
        scale = np.percentile(np.abs(rotation), 99)
        panels.append(("Cosserat rotation [rad]", rotation, "coolwarm", (-scale, scale)))
    fig, axes = plt.subplots(len(panels), 1, figsize=(9, 2.6 * len(panels)), sharex=True)
    for ax, (title, values, cmap, limits) in zip(np.atleast_1d(axes), panels):
        art = ax.scatter(x[:, 0], x[:, 1], c=values, s=2, cmap=cmap, vmin=limits[0],
                         vmax=limits[1], linewidths=0)
        ax.plot(face + slip["distance_m"], depth - slip["depth_m"], "c-", lw=1.5,
                label="Sokolovski slip line")
        ax.axvline(face, color="k", lw=2)
        ax.set_title(title, fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(face - 0.05, face + 3.0 * depth)
        ax.set_ylim(0, depth * 1.4)
        fig.colorbar(art, ax=ax, shrink=0.8)
    np.atleast_1d(axes)[0].legend(fontsize=7, loc="upper right")
    fig.suptitle("%s at %.1f mm of travel" % (label_of(run), best_travel * 1000))
    fig.tight_layout()
    fig.savefig(output / "fields.png", dpi=130)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", type=pathlib.Path)
    parser.add_argument("--output", type=pathlib.Path)
    args = parser.parse_args()
    output = args.output or args.runs[0]
    output.mkdir(parents=True, exist_ok=True)
    plot_forces(args.runs, output)
    plot_blade_stress(args.runs, output)
    plot_fields(args.runs[0], output)
    for name in ("forces.png", "blade_stress.png", "fields.png"):
        if (output / name).exists():
            print("wrote", output / name)


if __name__ == "__main__":
    main()
