"""PNG plots of DEM flat-blade runs (example_03_flat_blade --method dem), after Coetzee (2014):

    plot_dem_flat_blade.py forces RUN [RUN...] --out FILE        draft/vertical force vs travel
    plot_dem_flat_blade.py stress RUN --out FILE                 blade stresses (its Fig. 10)
    plot_dem_flat_blade.py pdr RUN [--at 15] --out FILE          PDR >= 0.15 map (its Fig. 11)
    plot_dem_flat_blade.py layers RUN --out FILE                 coloured layers (its Figs. 1-2)
    plot_dem_flat_blade.py depths RUN [RUN...] [--mpm RUN...] [--mpm-table 150:359.6,...] --out FILE
                                                                 average drafts vs depth (Fig. 8)
    plot_dem_flat_blade.py biaxial RUN [RUN...] --out FILE       biaxial test curves
    plot_dem_flat_blade.py network RUN [--frame 4] --out FILE    contact force network (HDF5 frame)

RUN is an output directory of the example. Forces are per metre of blade width (the DEM's unit
thickness); stresses compression positive at the blade.
"""
import argparse
import csv
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

# The paper's percentages (Sect. 3.2): nonpolar MPM = Sokolovski x (1.12, 1.06, 1.05) and
# = experiment x (1 - 0.25, 1 - 0.11, 1 - 0.09) at h = 150, 250, 350 mm (docs/validation.md).
PAPER_MPM_OVER_SOKOLOVSKI = {0.15: 1.12, 0.25: 1.06, 0.35: 1.05}
PAPER_MPM_UNDER_EXPERIMENT = {0.15: 0.25, 0.25: 0.11, 0.35: 0.09}


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]} if rows else {}


def summary(run):
    data = read_csv(os.path.join(run, "summary.csv"))
    return {k: v[0] for k, v in data.items()}


def label(run):
    s = summary(run)
    return f"h = {s['depth_m'] * 1000:.0f} mm ({series_name(run)})"


def plot_forces(runs, out):
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for i, run in enumerate(runs):
        f = read_csv(os.path.join(run, "forces.csv"))
        s = summary(run)
        colour = f"C{i}"
        travel = [1000 * d for d in f["displacement_m"]]
        ax1.plot(travel, f["draft_N_per_m"], color=colour, lw=0.8, label=label(run))
        ax2.plot(travel, f["vertical_N_per_m"], color=colour, lw=0.8)
        a, b = 1000 * s["average_from_m"], 1000 * s["average_to_m"]
        ax1.hlines(s["average_draft_N_per_m"], a, b, colors=colour, lw=2.5)
        ax1.axhline(s["sokolovski_draft_N_per_m"], color=colour, ls="--", lw=1)
        ax2.hlines(s["average_vertical_N_per_m"], a, b, colors=colour, lw=2.5)
        ax2.axhline(s["sokolovski_vertical_N_per_m"], color=colour, ls="--", lw=1)
    ax1.set_ylabel("draft force [N/m]")
    ax2.set_ylabel("vertical force [N/m]")
    ax2.set_xlabel("blade travel [mm]")
    ax1.set_title("DEM flat blade: force of the blade on the corn (thick: 15-35 mm average, "
                  "dashed: Sokolovski)", fontsize=9)
    ax1.legend(fontsize=8)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def plot_stress(run, out):
    p = read_csv(os.path.join(run, "blade_stress.csv"))
    w = read_csv(os.path.join(run, "sokolovski_wall.csv"))
    s = summary(run)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 5), sharey=True)
    depth = [1000 * d for d in p["depth_m"]]
    ax1.plot([x / 1000 for x in p["neighbour_normal_Pa"]], depth, "o-", ms=3,
             label="DEM: neighbouring contacts (the paper's estimate)")
    ax1.plot([x / 1000 for x in p["binned_normal_Pa"]], depth, "s--", ms=3, alpha=0.7,
             label="DEM: contact forces per 10 mm")
    ax1.plot([x / 1000 for x in w["normal_pressure_Pa"]], [1000 * d for d in w["depth_m"]], "k-",
             label="Sokolovski (778 kg/m$^3$)")
    ax2.plot([x / 1000 for x in p["neighbour_shear_Pa"]], depth, "o-", ms=3)
    ax2.plot([x / 1000 for x in p["binned_shear_Pa"]], depth, "s--", ms=3, alpha=0.7)
    ax2.plot([x / 1000 for x in w["shear_stress_Pa"]], [1000 * d for d in w["depth_m"]], "k-")
    ax1.set_xlabel("normal stress [kPa]")
    ax2.set_xlabel("shear stress [kPa]")
    ax1.set_ylabel("depth below the surface [mm]")
    ax1.invert_yaxis()
    ax1.legend(fontsize=7, loc="lower left")
    fig.suptitle(f"Blade stresses, DEM, h = {s['depth_m'] * 1000:.0f} mm, averaged over 18-22 mm "
                 "of travel", fontsize=10)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def disks(ax, part, colours, xlim=None):
    xs, ys = part["x_m"], part["y_m"]
    d = [2 * r for r in part["radius_m"]]
    coll = EllipseCollection(d, d, [0] * len(d), units="xy", offsets=list(zip(xs, ys)),
                             offset_transform=ax.transData, facecolors=colours,
                             edgecolors="none")
    ax.add_collection(coll)
    ax.set_aspect("equal")
    ax.set_xlim(xlim if xlim else (min(xs) - 0.01, max(xs) + 0.01))
    ax.set_ylim(0, max(ys) + 0.03)


def plot_pdr(run, at_mm, threshold, out):
    part = read_csv(os.path.join(run, f"particles_{at_mm}mm.csv"))
    slip = read_csv(os.path.join(run, "sokolovski_slip_line.csv"))
    s = summary(run)
    h = s["depth_m"]
    face = s["blade_face_x_m"] + at_mm / 1000
    fig, ax = plt.subplots(figsize=(10, 4.2))
    colours = ["0.15" if p >= threshold else "0.8" for p in part["pdr"]]
    disks(ax, part, colours, (face - 0.05, face + 2.6 * h))
    ax.plot([face + d for d in slip["distance_m"]], [h - z for z in slip["depth_m"]], "r-", lw=2,
            label="Sokolovski slip line")
    ax.axvline(face, color="k", lw=3)
    moved = sum(1 for p in part["pdr"] if p >= threshold)
    ax.set_title(f"DEM, h = {h * 1000:.0f} mm, blade travel {at_mm} mm: dark disks have "
                 f"PDR >= {threshold} ({moved} of {len(part['pdr'])})", fontsize=9)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(out, dpi=150)


def plot_layers(run, out):
    snaps = sorted(int(f[len("particles_"):-len("mm.csv")]) for f in os.listdir(run)
                   if f.startswith("particles_") and f.endswith("mm.csv"))
    snaps = [t for t in snaps if t >= 100] or snaps
    s = summary(run)
    rows = (len(snaps) + 1) // 2
    fig, axes = plt.subplots(rows, 2, figsize=(13, 3.3 * rows), squeeze=False)
    palette = ["#1f4e9a", "#e0b000", "#b0202a", "#2a8a3a", "#7a4a9a", "#e07020", "#20a0b0"]
    for ax, t in zip(axes.flat, snaps):
        part = read_csv(os.path.join(run, f"particles_{t}mm.csv"))
        colours = [palette[int(k) % len(palette)] for k in part["layer"]]
        face = s["blade_face_x_m"] + t / 1000
        disks(ax, part, colours, (face - 0.05, face + 0.65))
        ax.axvline(face, color="k", lw=3)
        ax.set_title(f"blade travel {t} mm", fontsize=9)
        ax.set_ylim(0, 0.42)
    for ax in list(axes.flat)[len(snaps):]:
        ax.axis("off")
    fig.suptitle(f"DEM, h = {s['depth_m'] * 1000:.0f} mm: layers coloured by initial height",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def series_name(run):
    """A run directory's name without its depth: runs of one series differ only in h."""
    name = os.path.basename(os.path.normpath(run))
    return re.sub(r"_?h0?\.?[0-9]+$", "", name) or name


def plot_depths(runs, mpm_runs, mpm_table, out):
    fig, ax = plt.subplots(figsize=(8, 5.5))
    groups = {}
    for r in runs:
        groups.setdefault(series_name(r), []).append(summary(r))
    soko = {}
    for i, (name, sums) in enumerate(sorted(groups.items())):
        sums.sort(key=lambda s: s["depth_m"])
        ax.plot([1000 * s["depth_m"] for s in sums], [s["average_draft_N_per_m"] for s in sums],
                "o-", color=f"C{i}", label=f"DEM: {name}")
        for s in sums:
            soko[round(s["depth_m"], 4)] = s["sokolovski_draft_N_per_m"]
    depths = sorted(soko)
    ax.plot([1000 * d for d in depths], [soko[d] for d in depths], "k--",
            label="Sokolovski (phi 26, delta 14 deg, 778 kg/m$^3$)")
    exp = [(1000 * d, PAPER_MPM_OVER_SOKOLOVSKI[d] * soko[d] / (1 - PAPER_MPM_UNDER_EXPERIMENT[d]))
           for d in depths if d in PAPER_MPM_OVER_SOKOLOVSKI]
    if exp:
        ax.plot(*zip(*exp), "s", color="C3", ms=7, label="experiment (from the paper's percentages)")
        ax.fill_between([x for x, _ in exp], [0.94 * y for _, y in exp],
                        [1.12 * y for _, y in exp], color="C3", alpha=0.12,
                        label="the paper's DEM: -6 % to +12 % of experiment")
    mpm = [(summary(r)["depth_m"], summary(r)["average_draft_N_per_m"]) for r in mpm_runs]
    for item in mpm_table.split(",") if mpm_table else []:
        h, f = item.split(":")
        mpm.append((float(h) / 1000, float(f)))
    if mpm:
        mpm.sort()
        ax.plot([1000 * d for d, _ in mpm], [f for _, f in mpm], "^-", color="0.4",
                label="nonpolar MPM (this toolkit, 120 x 70)")
    ax.set_xlabel("blade depth h [mm]")
    ax.set_ylabel("average draft force over 15-35 mm [N/m]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def plot_network(run, frame, out):
    import h5py  # only this plot reads the HDF5 frames
    import numpy as np
    from matplotlib.collections import LineCollection

    path = os.path.join(run, "frames", f"dem_flat_blade_{frame:06d}.h5")
    with h5py.File(path, "r") as f:
        x = f["/particles/position"][:]
        r = f["/particles/radius"][:]
        points = f["/contacts/points"][:, :2].reshape(-1, 2, 2)
        force = f["/contacts/force"][:]
        walls = f["/walls/points"][:, :2].reshape(-1, 2, 2)
        time = f.attrs["time"]
    s = summary(run)
    fig, ax = plt.subplots(figsize=(11, 4.6))
    coll = EllipseCollection(2 * r, 2 * r, np.zeros_like(r), units="xy", offsets=x,
                             offset_transform=ax.transData, facecolors="0.88",
                             edgecolors="none")
    ax.add_collection(coll)
    scale = np.percentile(force, 99)
    order = np.argsort(force)
    lines = LineCollection(points[order], linewidths=0.2 + 2.5 * force[order] / scale,
                           colors=plt.cm.inferno_r(0.15 + 0.85 * np.clip(force[order] / scale, 0, 1)))
    ax.add_collection(lines)
    ax.add_collection(LineCollection(walls, colors="k", linewidths=2.5))
    face = s["blade_face_x_m"]
    ax.set_xlim(face - 0.03, face + 2.4 * s["depth_m"])
    ax.set_ylim(-0.005, s["depth_m"] + 0.06)
    ax.set_aspect("equal")
    ax.set_title(f"DEM contact force network, h = {s['depth_m'] * 1000:.0f} mm, frame {frame} "
                 f"(t = {time:.2f} s); line width and colour: contact force (99th percentile "
                 f"{scale:.0f} N/m)", fontsize=9)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(out, dpi=150)


def plot_biaxial(runs, out):
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    for i, run in enumerate(runs):
        c = read_csv(os.path.join(run, "biaxial.csv"))
        s = summary(run)
        strain = [100 * e for e in c["axial_strain"]]
        grains = f"mu = {s['friction']:g}"
        if "rolling_friction" in s:  # older summaries lack the shape and the rolling friction
            grains += f", mu_r = {s['rolling_friction']:g}, aspect {s['aspect']:g}"
            if s["packing_friction"] != s["friction"]:
                grains += f", packed at mu = {s['packing_friction']:g}"
        else:
            grains = os.path.basename(os.path.normpath(run))
        name = (f"{grains}, s3 = {s['confining_stress_Pa'] / 1000:g} kPa: peak "
                f"{s['peak_angle_deg']:.1f}, critical {s['critical_angle_deg']:.1f} deg")
        ax1.plot(strain, c["friction_angle_deg"], color=f"C{i}", lw=0.8, label=name)
        ax1.axhline(s["critical_angle_deg"], color=f"C{i}", ls=":", lw=1)
        ax2.plot(strain, [100 * v for v in c["volumetric_strain"]], color=f"C{i}", lw=0.8)
    ax1.axhline(26, color="k", ls="--", lw=1, label="corn, shear box (Table 1): 26 deg")
    ax1.set_ylabel("mobilised friction angle [deg]")
    ax2.set_ylabel("area change [%] (dilation +)")
    ax2.set_xlabel("axial strain [%]")
    ax1.legend(fontsize=7)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("kind", choices=["forces", "stress", "pdr", "layers", "depths", "biaxial",
                                         "network"])
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--mpm", nargs="*", default=[], help="MPM run directories")
    parser.add_argument("--mpm-table", default="",
                        help="MPM drafts as h_mm:N_per_m,... (e.g. from docs/validation.md)")
    parser.add_argument("--at", type=int, default=15)
    parser.add_argument("--frame", type=int, default=4)
    parser.add_argument("--threshold", type=float, default=0.15)
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    if a.kind == "forces":
        plot_forces(a.runs, a.out)
    elif a.kind == "stress":
        plot_stress(a.runs[0], a.out)
    elif a.kind == "pdr":
        plot_pdr(a.runs[0], a.at, a.threshold, a.out)
    elif a.kind == "layers":
        plot_layers(a.runs[0], a.out)
    elif a.kind == "depths":
        plot_depths(a.runs, a.mpm, a.mpm_table, a.out)
    elif a.kind == "network":
        plot_network(a.runs[0], a.frame, a.out)
    else:
        plot_biaxial(a.runs, a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
