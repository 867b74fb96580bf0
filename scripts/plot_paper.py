#!/usr/bin/python3
"""The figures of Coetzee (2014) from the runs of scripts/reproduce_paper.sh.

usage: /usr/bin/python3 scripts/plot_paper.py OUT [--wall-seconds S] [--meshes FINE COARSE]
                                               [--quick]

Reads OUT/runs/NAME (the flat-blade driver's output folders, MPM and DEM) and writes into OUT
one PNG per figure of the paper (fig01_02_flow.png, fig03_free_surface.png,
fig06_forces_psi.png, fig07_forces_depth.png, fig08_draft_depth.png, fig09_blade_stress.png,
fig10_dem_blade_stress.png, fig11_pdr.png, fig12_13_yield_shear.png), drafts.csv (Fig. 8's
numbers) and report.md: each figure beside the statement the paper makes about it, with our
numbers and the runs' times. A run that stopped early is drawn as far as it went and named in
the report.
"""
import argparse
import csv
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_flat_blade import read_csv, read_frame  # noqa: E402

# The paper's percentages (Sect. 3.2) at h = 150, 250, 350 mm. Its nonpolar MPM draft is
# Sokolovski's x (1.12, 1.06, 1.05); the same MPM draft is (25, 11, 9) % below the experiment,
# so experiment = paper MPM / (1 - 0.25, 0.11, 0.09); its polar MPM is (28, 14, 10) % below its
# nonpolar MPM; its DEM lies between 6 % below and 12 % above the experiment (Sect. 4).
PAPER_DEPTHS = (0.15, 0.25, 0.35)
PAPER_MPM_OVER_SOKOLOVSKI = (1.12, 1.06, 1.05)
PAPER_MPM_BELOW_EXPERIMENT = (0.25, 0.11, 0.09)
PAPER_POLAR_BELOW_NONPOLAR = (0.28, 0.14, 0.10)
PAPER_DEM_RANGE = (-0.06, 0.12)
LAYER_THICKNESS = 0.025  # m, the coloured bands of Figs. 1-2
DPI = 100


class Run:
    """One output folder of example_03_flat_blade, complete or stopped early."""

    def __init__(self, folder):
        self.folder = folder
        self.name = folder.name
        self.case = {}
        for line in (folder / "case.used").read_text().splitlines():
            line = line.split("#", 1)[0].strip()
            if "=" in line:
                key, value = (part.strip() for part in line.split("=", 1))
                self.case[key] = value
        self.summary = (read_csv(folder / "summary.csv") if (folder / "summary.csv").exists()
                        else None)
        forces = folder / "forces.csv"
        self.forces = read_csv(forces) if forces.exists() else None
        self.frames = sorted((folder / "frames").glob("flat_blade_*.h5"))

    def number(self, key):
        return float(self.case[key])

    @property
    def polar(self):
        return self.case.get("polar") == "true" or self.case.get("material") == (
            "cosserat-drucker-prager")

    @property
    def depth(self):
        return self.number("depth")

    @property
    def mesh(self):
        return "%dx%d" % (int(self.number("cells-x")), int(self.number("cells-y")))

    @property
    def travel_reached(self):
        if self.forces is None or len(self.forces["displacement_m"]) == 0:
            return 0.0
        return float(self.forces["displacement_m"][-1])

    @property
    def complete(self):
        return self.summary is not None

    def average_draft(self):
        """The 15-35 mm average draft [N/m] the driver reports; for a run that stopped after
        the window, the mean of its recorded forces there; None if it stopped before."""
        if self.summary is not None:
            return float(self.summary["average_draft_N_per_m"][0])
        start, end = self.number("average-from"), self.number("average-to")
        if self.forces is None or self.travel_reached < end:
            return None
        d = self.forces["displacement_m"]
        return float(self.forces["draft_N_per_m"][(d >= start) & (d <= end)].mean())

    def sokolovski_draft(self):
        return None if self.summary is None else float(self.summary["sokolovski_draft_N_per_m"][0])

    def frame_at(self, travel):
        """The frame nearest `travel` of blade travel [m], with its travel, or (None, None)."""
        import h5py

        best, best_travel = None, None
        for path in self.frames:
            with h5py.File(path, "r") as h5:
                if "values/blade_travel" not in h5:
                    continue
                t = float(np.ravel(h5["values/blade_travel"][()])[0])
            if best is None or abs(t - travel) < abs(best_travel - travel):
                best, best_travel = path, t
        if best is None or abs(best_travel - travel) > 0.01:
            return None, None
        return best, best_travel

    def label(self):
        text = "%s, h = %.0f mm" % ("polar" if self.polar else "nonpolar", self.depth * 1000)
        psi = self.case.get("psi", "2")
        text += ", psi = %s" % psi
        if self.case.get("floor") == "friction":
            text += ", Coulomb floor"
        if float(self.case.get("dilatancy-cutoff", "0")) > 0:
            text += ", cut-off %s" % self.case["dilatancy-cutoff"]
        if float(self.case.get("flip", "1")) < 1:
            text += ", %.0f %% PIC" % (100 * (1 - float(self.case["flip"])))
        rotation = self.case.get("blade-rotation", "held")
        if self.case.get("blade-rotation-fixed") == "false":  # older case files
            rotation = "free"
        if self.polar and rotation != "held":
            text += ", %s rotation" % rotation
        if not self.complete:
            text += " (stopped at %.0f mm)" % (self.travel_reached * 1000)
        return text


class DemRun:
    """One output folder of example_03_flat_blade --method dem (runs dem_flow, dem_hH)."""

    def __init__(self, folder):
        self.folder = folder
        self.name = folder.name
        self.summary = (read_csv(folder / "summary.csv") if (folder / "summary.csv").exists()
                        else None)
        self.forces = read_csv(folder / "forces.csv") if (folder / "forces.csv").exists() else None
        self.packing = (read_csv(folder / "packing.csv") if (folder / "packing.csv").exists()
                        else None)

    @property
    def depth(self):
        return 0.2 if self.name == "dem_flow" else float(self.name[len("dem_h"):])

    @property
    def complete(self):
        return self.summary is not None

    @property
    def travel_reached(self):
        if self.forces is None or len(self.forces["displacement_m"]) == 0:
            return 0.0
        return float(self.forces["displacement_m"][-1])

    def value(self, key):
        return None if self.summary is None else float(self.summary[key][0])

    def average_draft(self):
        return self.value("average_draft_N_per_m")

    def blade_face(self):
        """x of the blade's face before cutting (the driver's default if the run stopped)."""
        face = self.value("blade_face_x_m")
        return 0.06 if face is None else face

    def snapshot(self, travel):
        """The particles_<mm>mm.csv snapshot at `travel` [m], or None."""
        path = self.folder / ("particles_%dmm.csv" % round(travel * 1000))
        return read_csv(path) if path.exists() else None

    def label(self):
        text = "DEM, h = %.0f mm" % (self.depth * 1000)
        if not self.complete:
            text += " (stopped at %.0f mm)" % (self.travel_reached * 1000)
        return text


def draw_disks(ax, part, colours):
    diameter = 2 * part["radius_m"]
    ax.add_collection(EllipseCollection(diameter, diameter, np.zeros_like(diameter), units="xy",
                                        offsets=np.column_stack([part["x_m"], part["y_m"]]),
                                        offset_transform=ax.transData, facecolors=colours,
                                        edgecolors="none"))


def dem_blade_outline(run, travel, height=0.35, thickness=0.01):
    face = run.blade_face() + travel
    return np.array([[face - thickness, 0], [face, 0], [face, height], [face - thickness, height],
                     [face - thickness, 0]])


def scatter_particles(ax, run, x, **style):
    """Particles as squares of their initial spacing (cell / particles per cell), sized for
    the axes' current limits, so a particle field reads as a continuum at any mesh."""
    spacing = run.number("grid-length") / run.number("cells-x") / run.number(
        "particles-per-cell")
    fig = ax.figure
    fig.canvas.draw()
    pixels_per_metre = ax.bbox.width / abs(np.diff(ax.get_xlim())[0])
    side = max(spacing * pixels_per_metre * 72.0 / fig.dpi, 0.5)
    return ax.scatter(x[:, 0], x[:, 1], s=side ** 2, marker="s", linewidths=0, **style)


def blade_outline(path):
    import h5py

    with h5py.File(path, "r") as h5:
        if "bodies/blade/vertices" not in h5:
            return None
        vertices = h5["bodies/blade/vertices"][()][:, :2]
    return np.vstack([vertices, vertices[:1]])


def particles_of(path):
    import h5py

    with h5py.File(path, "r") as h5:
        group = h5["particles"]
        return group["position"][()][:, :2], group["initial_position"][()][:, :2]


def free_surface(position, cell):
    """The top of the particles in each column of the grid [x, y]: the highest particle in
    the column plus half a particle spacing (2 particles per cell), columns without particles
    left out."""
    column = np.floor(position[:, 0] / cell).astype(int)
    xs, ys = [], []
    for c in np.unique(column):
        xs.append((c + 0.5) * cell)
        ys.append(position[column == c, 1].max() + cell / 4)
    return np.array(xs), np.array(ys)


def plot_flow(runs, out):
    travels = (0.1, 0.2, 0.3, 0.4)
    flows = [runs[n] for n in ("flow_psi2", "flow_psi10", "flow_psi26", "dem_flow") if n in runs]
    if not flows:
        return None
    fig, axes = plt.subplots(len(travels), len(flows), figsize=(4.2 * len(flows), 7.5),
                             squeeze=False, sharex=True, sharey=True)
    colours = np.array([[0.85, 0.65, 0.13], [0.2, 0.35, 0.65]])
    for column, run in enumerate(flows):
        for row, travel in enumerate(travels):
            ax = axes[row, column]
            ax.set_xlim(0.0, 1.0)
            ax.set_ylim(0.0, 0.45)
            ax.set_aspect("equal")
            if isinstance(run, DemRun):
                part = run.snapshot(travel)
                if part is None:
                    ax.text(0.5, 0.5, "not reached", transform=ax.transAxes, ha="center")
                else:
                    # The driver numbers layers of --layer-thickness (25 mm here) from the floor.
                    draw_disks(ax, part, colours[part["layer"].astype(int) % 2])
                    outline = dem_blade_outline(run, travel)
                    ax.fill(outline[:, 0], outline[:, 1], color="0.3")
                    ax.text(0.02, 0.9, "%.0f mm" % (travel * 1000), transform=ax.transAxes,
                            fontsize=8)
                if row == 0:
                    ax.set_title("DEM%s" % ("" if run.complete else " (stopped at %.0f mm)"
                                            % (run.travel_reached * 1000)), fontsize=9)
                continue
            path, reached = run.frame_at(travel)
            if path is None:
                ax.text(0.5, 0.5, "not reached", transform=ax.transAxes, ha="center")
            else:
                x, x0 = particles_of(path)
                band = np.floor(x0[:, 1] / LAYER_THICKNESS).astype(int) % 2
                scatter_particles(ax, run, x, c=colours[band])
                outline = blade_outline(path)
                if outline is not None:
                    ax.fill(outline[:, 0], outline[:, 1], color="0.3")
                ax.text(0.02, 0.9, "%.0f mm" % (reached * 1000), transform=ax.transAxes,
                        fontsize=8)
            if row == 0:
                ax.set_title("psi = %s deg%s" % (run.case["psi"], "" if run.complete else
                                                 " (stopped at %.0f mm)" %
                                                 (run.travel_reached * 1000)), fontsize=9)
    mpm = [run for run in flows if not isinstance(run, DemRun)]
    fig.suptitle("Figs. 1-2: nonpolar MPM%s, h = 200 mm, layers of %.0f mm%s"
                 % (" and DEM" if len(mpm) < len(flows) else "", LAYER_THICKNESS * 1000,
                    ", mesh %s" % mpm[0].mesh if mpm else ""))
    fig.tight_layout()
    name = "fig01_02_flow.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name


def plot_free_surfaces(runs, out):
    travels = (0.1, 0.2, 0.3, 0.4)
    flows = [runs[n] for n in ("flow_psi2", "flow_psi10", "flow_psi26") if n in runs]
    if not flows:
        return None, []
    fig, axes = plt.subplots(2, 2, figsize=(10, 6), sharex=True, sharey=True)
    heights = []
    for ax, travel in zip(axes.ravel(), travels):
        for run in flows:
            path, reached = run.frame_at(travel)
            if path is None:
                continue
            cell = run.number("grid-length") / run.number("cells-x")
            x, _ = particles_of(path)
            outline = blade_outline(path)
            if outline is not None:
                # The soil the blade pushes: a particle thrown behind it is not its surface.
                x = x[x[:, 0] > outline[:, 0].max()]
            xs, ys = free_surface(x, cell)
            ax.plot(xs, ys * 1000, "-", label="psi = %s deg" % run.case["psi"])
            ahead = xs > x[:, 0].min() + 0.05
            heights.append((run.case["psi"], travel, float(ys[ahead].max())))
        ax.axhline(200, color="0.5", ls=":", lw=1, label="initial surface")
        ax.set_title("%.0f mm of travel" % (travel * 1000), fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[1, 0].set_xlabel("x [m]")
    axes[1, 1].set_xlabel("x [m]")
    axes[0, 0].set_ylabel("free surface [mm]")
    axes[1, 0].set_ylabel("free surface [mm]")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Fig. 3: free surfaces for three dilatancy angles (nonpolar MPM, h = 200 mm)")
    fig.tight_layout()
    name = "fig03_free_surface.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name, heights


def plot_forces(selection, title, name, out):
    if not selection:
        return None
    fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    width = None
    for i, run in enumerate(selection):
        if run.forces is None:
            continue
        width = run.number("rig-width")
        d = run.forces["displacement_m"] * 1000
        axes[0].plot(d, run.forces["draft_N_rig"], color="C%d" % i, lw=0.8, label=run.label())
        axes[1].plot(d, run.forces["vertical_N_rig"], color="C%d" % i, lw=0.8)
    axes[0].axvspan(15, 35, color="0.9", zorder=0, label="the paper's averaging window")
    axes[0].set_ylabel("draft [N] (%.0f mm rig)" % (width * 1000))
    axes[1].set_ylabel("vertical force [N]")
    axes[1].set_xlabel("blade displacement [mm]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name


def draft_table(runs):
    """Fig. 8's numbers: per depth, Sokolovski, ours (fixed floor, Coulomb floor, polar) and
    the experiment, the paper's MPM and polar MPM derived from the paper's percentages."""
    rows = []
    for k, depth in enumerate(PAPER_DEPTHS):
        nonpolar = runs.get("h%g" % depth)
        floor = runs.get("h%g_floor" % depth) or runs.get("h%g_psi2_floor" % depth)
        polar = runs.get("polar_h%g" % depth)
        dem = runs.get("dem_h%g" % depth)
        sokolovski = next((r.sokolovski_draft() for r in (nonpolar, floor, polar)
                           if r is not None and r.sokolovski_draft() is not None), None)
        if sokolovski is None and dem is not None:
            sokolovski = dem.value("sokolovski_draft_N_per_m")
        row = {"depth_m": depth, "sokolovski": sokolovski,
               "nonpolar_fixed_floor": nonpolar.average_draft() if nonpolar else None,
               "nonpolar_coulomb_floor": floor.average_draft() if floor else None,
               "polar": polar.average_draft() if polar else None,
               "dem": dem.average_draft() if dem else None}
        if sokolovski is not None:
            paper_mpm = sokolovski * PAPER_MPM_OVER_SOKOLOVSKI[k]
            row["paper_nonpolar"] = paper_mpm
            row["paper_polar"] = paper_mpm * (1 - PAPER_POLAR_BELOW_NONPOLAR[k])
            row["experiment"] = paper_mpm / (1 - PAPER_MPM_BELOW_EXPERIMENT[k])
        rows.append(row)
    return rows


def plot_drafts(rows, out):
    fig, ax = plt.subplots(figsize=(7, 5))
    depth = np.array([r["depth_m"] for r in rows]) * 1000

    def series(key):
        return np.array([np.nan if r.get(key) is None else r[key] for r in rows])

    ax.plot(depth, series("sokolovski"), "k-", label="Sokolovski")
    experiment = series("experiment")
    ax.plot(depth, experiment, "s", color="C3", ms=7,
            label="experiment (derived from the paper's percentages)")
    ax.fill_between(depth, experiment * (1 + PAPER_DEM_RANGE[0]),
                    experiment * (1 + PAPER_DEM_RANGE[1]), color="C3", alpha=0.12,
                    label="the paper's DEM: -6 % to +12 % of experiment")
    ax.plot(depth, series("paper_nonpolar"), "x", color="C0", ms=8,
            label="the paper's nonpolar MPM (derived)")
    ax.plot(depth, series("paper_polar"), "x", color="C1", ms=8,
            label="the paper's polar MPM (derived)")
    ax.plot(depth, series("nonpolar_fixed_floor"), "o-", color="C0",
            label="ours: nonpolar, fixed floor")
    ax.plot(depth, series("nonpolar_coulomb_floor"), "o--", color="C2",
            label="ours: nonpolar, Coulomb floor")
    ax.plot(depth, series("polar"), "o-", color="C1", label="ours: polar, fixed floor")
    if np.isfinite(series("dem")).any():
        ax.plot(depth, series("dem"), "D-", color="C4", label="ours: DEM, calibrated grains")
    ax.set_xlabel("blade depth h [mm]")
    ax.set_ylabel("average draft, 15-35 mm [N/m]")
    ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Fig. 8: average draft against depth")
    fig.tight_layout()
    name = "fig08_draft_depth.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name


def mpm_blade_profile(folder):
    """An MPM run's blade_stress.csv over the buried face: depth [mm], normal and shear [kPa]."""
    profile = read_csv(folder / "blade_stress.csv")
    keep = (profile["depth_m"] >= -1e-9) & (profile["nodes"] > 0)
    return (profile["depth_m"][keep] * 1000, profile["normal_traction_Pa"][keep] / 1000,
            profile["shear_traction_Pa"][keep] / 1000)


def plot_sokolovski_wall(axes, folder):
    wall = read_csv(folder / "sokolovski_wall.csv")
    axes[0].plot(wall["normal_pressure_Pa"] / 1000, wall["depth_m"] * 1000, "k--",
                 label="Sokolovski")
    axes[1].plot(wall["shear_stress_Pa"] / 1000, wall["depth_m"] * 1000, "k--")
    return wall


def label_stress_axes(axes):
    """Normal (left) and shear (right) stress against depth, the surface at the top."""
    axes[0].set_xlabel("normal stress on the blade [kPa]")
    axes[1].set_xlabel("shear stress on the blade [kPa]")
    axes[0].set_ylabel("depth below the initial surface [mm]")
    axes[0].invert_yaxis()
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)


def plot_blade_stress(selection, out):
    selection = [r for r in selection if (r.folder / "blade_stress.csv").exists()]
    if not selection:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(9, 5), sharey=True)
    for i, run in enumerate(selection):
        depth, normal, shear = mpm_blade_profile(run.folder)
        axes[0].plot(normal, depth, "o-", ms=3, color="C%d" % i, label=run.label())
        axes[1].plot(shear, depth, "o-", ms=3, color="C%d" % i)
    plot_sokolovski_wall(axes, selection[0].folder)
    label_stress_axes(axes)
    fig.suptitle("Fig. 9: blade stresses, h = 350 mm, 20 mm of travel")
    fig.tight_layout()
    name = "fig09_blade_stress.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name


def plot_dem_blade_stress(dem, mpm, out):
    """Fig. 10: the DEM's blade stresses (the paper's estimate: two neighbouring contacts'
    mean force over their distance, 18-22 mm of travel), Sokolovski's and our nonpolar MPM's."""
    if dem is None or not (dem.folder / "blade_stress.csv").exists():
        return None, None
    profile = read_csv(dem.folder / "blade_stress.csv")
    keep = profile["samples"] > 0
    fig, axes = plt.subplots(1, 2, figsize=(9, 5), sharey=True)
    depth = profile["depth_m"][keep] * 1000
    for ax, key in zip(axes, ("normal", "shear")):
        ax.plot(profile["neighbour_%s_Pa" % key][keep] / 1000, depth, "o-", ms=3, color="C3",
                label="DEM: neighbouring contacts (the paper's estimate)")
        ax.plot(profile["binned_%s_Pa" % key][keep] / 1000, depth, "s:", ms=3, color="C3",
                alpha=0.6, label="DEM: contact forces per 10 mm bin")
    wall = plot_sokolovski_wall(axes, dem.folder)
    numbers = {"dem": (float(np.mean(profile["neighbour_normal_Pa"][keep])) / 1000,
                       float(np.mean(profile["neighbour_shear_Pa"][keep])) / 1000)}
    inside = (wall["depth_m"] >= 0) & (wall["depth_m"] <= dem.depth)
    numbers["sokolovski"] = (float(np.mean(wall["normal_pressure_Pa"][inside])) / 1000,
                             float(np.mean(wall["shear_stress_Pa"][inside])) / 1000)
    if mpm is not None and (mpm.folder / "blade_stress.csv").exists():
        depth, normal, shear = mpm_blade_profile(mpm.folder)
        axes[0].plot(normal, depth, "o-", ms=3, color="C0",
                     label="ours: nonpolar MPM (%s)" % mpm.mesh)
        axes[1].plot(shear, depth, "o-", ms=3, color="C0")
        numbers["mpm"] = (float(np.mean(normal)), float(np.mean(shear)))
    label_stress_axes(axes)
    fig.suptitle("Fig. 10: blade stresses, DEM, h = %.0f mm, 18-22 mm of travel"
                 % (dem.depth * 1000))
    fig.tight_layout()
    name = "fig10_dem_blade_stress.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name, numbers


def fields_at(run, travel):
    """Position, plastic flag, J' and PDR at the frame nearest `travel`, strains counted from
    the frame at the blade's start (the paper's Figs. 11-13)."""
    path, reached = run.frame_at(travel)
    first, start = run.frame_at(0.0)
    if path is None or first is None:
        return None
    frame, origin = read_frame(path), read_frame(first)
    exx = frame["strain_xx"] - origin["strain_xx"]
    eyy = frame["strain_yy"] - origin["strain_yy"]
    exy = frame["strain_xy"] - origin["strain_xy"]
    j2 = ((exx - eyy) ** 2 + eyy ** 2 + exx ** 2) / 6.0 + exy ** 2
    pdr = np.linalg.norm(frame["position"] - origin["position"], axis=1) / max(reached - start,
                                                                              1e-12)
    return {"x": frame["position"], "plastic": frame["plastic"], "j2": j2, "pdr": pdr,
            "travel": reached, "outline": blade_outline(path)}


def slip_line_panel(ax, folder, depth, face, outline):
    """The wedge ahead of a blade face at x = face: Sokolovski's slip line, the blade."""
    slip = read_csv(folder / "sokolovski_slip_line.csv")
    ax.plot(face + slip["distance_m"], depth - slip["depth_m"], "c-", lw=1.2, zorder=3,
            label="Sokolovski slip line")
    if outline is not None:
        ax.fill(outline[:, 0], outline[:, 1], color="0.5", zorder=3)
    ax.set_aspect("equal")
    ax.set_xlim(face - 0.03, face + 2.6 * depth)
    ax.set_ylim(0, depth * 1.3)


def decorate(ax, run, fields):
    face = float(run.case.get("blade-start", "0.05")) + float(
        run.case.get("blade-thickness", "0.01")) + fields["travel"]
    slip_line_panel(ax, run.folder, run.depth, face, fields["outline"])


def dem_pdr_panel(ax, run, at=0.015, threshold=0.15):
    part = run.snapshot(at)
    dark = part["pdr"] >= threshold
    draw_disks(ax, part, np.where(dark, "0.15", "0.8"))
    slip_line_panel(ax, run.folder, run.depth, run.blade_face() + at, dem_blade_outline(run, at))
    ax.set_title("%s: PDR >= %.2f dark (%d of %d disks), %.0f mm of travel"
                 % (run.label(), threshold, int(dark.sum()), len(dark), at * 1000), fontsize=9)


def plot_pdr(selection, out, dem=None):
    panels = [(run, fields_at(run, 0.015)) for run in selection]
    panels = [(run, f) for run, f in panels if f is not None]
    if dem is not None and dem.snapshot(0.015) is not None:
        panels.insert(0, (dem, None))  # the paper's top panel
    if not panels:
        return None
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 2.8 * len(panels)), squeeze=False)
    for ax, (run, fields) in zip(axes[:, 0], panels):
        if isinstance(run, DemRun):
            dem_pdr_panel(ax, run)
            continue
        dark = fields["pdr"] >= 0.15
        decorate(ax, run, fields)
        scatter_particles(ax, run, fields["x"], c=np.where(dark, 0.15, 0.8), cmap="Greys_r",
                          vmin=0, vmax=1)
        ax.set_title("%s, %s: PDR >= 0.15 dark, %.1f mm of travel"
                     % (run.label(), run.mesh, fields["travel"] * 1000), fontsize=9)
    axes[0, 0].legend(fontsize=7, loc="upper right")
    fig.suptitle("Fig. 11: slip lines from the particle displacement ratio")
    fig.tight_layout()
    name = "fig11_pdr.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name


def band_width(run, fields):
    """Width [m] of the J' band across Sokolovski's slip line at mid-depth: the extent, normal
    to the line, of the particles within 1.5 cells of the line's mid-point plane whose J' is
    above half the band's peak there."""
    slip = read_csv(run.folder / "sokolovski_slip_line.csv")
    face = float(run.case.get("blade-start", "0.05")) + float(
        run.case.get("blade-thickness", "0.01")) + fields["travel"]
    line = np.column_stack([face + slip["distance_m"], run.depth - slip["depth_m"]])
    mid = len(line) // 2
    point = line[mid]
    tangent = line[min(mid + 1, len(line) - 1)] - line[max(mid - 1, 0)]
    tangent /= np.linalg.norm(tangent)
    normal = np.array([-tangent[1], tangent[0]])
    cell = run.number("grid-length") / run.number("cells-x")
    relative = fields["x"] - point
    along, across = relative @ tangent, relative @ normal
    near = (np.abs(along) < 1.5 * cell) & (np.abs(across) < 0.1)
    if near.sum() < 3:
        return None
    j2 = fields["j2"][near]
    high = across[near][j2 >= 0.5 * j2.max()]
    return float(high.max() - high.min())


def plot_yield_and_shear(selection, out):
    panels = [(run, fields_at(run, 0.015)) for run in selection]
    panels = [(run, f) for run, f in panels if f is not None]
    if not panels:
        return None, {}
    fig, axes = plt.subplots(len(panels), 2, figsize=(13, 2.9 * len(panels)), squeeze=False)
    numbers = {}
    for row, (run, fields) in enumerate(panels):
        ax = axes[row, 0]
        decorate(ax, run, fields)
        scatter_particles(ax, run, fields["x"], c=fields["plastic"], vmin=0, vmax=1,
                          cmap=matplotlib.colors.ListedColormap(["0.2", "#f4d35e"]))
        ax.set_title("Fig. 12, %s: yield points (yellow; elastic dark), %.1f mm" % (run.mesh,
                                                                     fields["travel"] * 1000),
                     fontsize=9)
        ax = axes[row, 1]
        decorate(ax, run, fields)
        scatter_particles(ax, run, fields["x"], c=fields["j2"], cmap="magma", vmin=0,
                          vmax=np.percentile(fields["j2"], 99))
        ax.set_title("Fig. 13, %s: shear strain intensity J' (light: high)" % run.mesh,
                     fontsize=9)
        in_front = fields["x"][:, 0] > fields["outline"][:, 0].max() if fields[
            "outline"] is not None else np.ones(len(fields["x"]), bool)
        numbers[run.mesh] = {"yield_fraction": float(fields["plastic"][in_front].mean()),
                             "band_width_m": band_width(run, fields)}
    axes[0, 0].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    name = "fig12_13_yield_shear.png"
    fig.savefig(out / name, dpi=DPI)
    plt.close(fig)
    return name, numbers


def fmt(value, pattern="%.1f"):
    return "-" if value is None else pattern % value


def percent(value, reference):
    if value is None or reference is None:
        return "-"
    return "%+.1f %%" % (100 * (value / reference - 1))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--wall-seconds", type=float)
    parser.add_argument("--meshes", nargs=2, default=("120x70", "80x50"))
    parser.add_argument("--quick", action="store_true", help="the runs of --quick (CI)")
    args = parser.parse_args()
    out = args.out
    runs = {}
    for folder in sorted((out / "runs").iterdir()):
        if folder.is_dir() and (folder / "case.used").exists():
            runs[folder.name] = Run(folder)
        elif folder.is_dir() and folder.name.startswith("dem_"):
            runs[folder.name] = DemRun(folder)
    if not runs:
        raise SystemExit("plot_paper.py: no runs in %s/runs" % out)

    def pick(*names):
        return [runs[n] for n in names if n in runs]

    figures = {}
    figures["flow"] = plot_flow(runs, out)
    figures["surface"], heights = plot_free_surfaces(runs, out)
    figures["psi"] = plot_forces(
        pick("fig6_psi2", "fig6_psi10", "fig6_psi26", "polar_h0.35"),
        "Fig. 6: blade forces for three dilatancy angles, h = 350 mm", "fig06_forces_psi.png",
        out)
    figures["depth"] = plot_forces(pick("fig7_h0.15", "fig7_h0.25", "fig6_psi2"),
                                   "Fig. 7: blade forces at three depths (nonpolar, psi = 2)",
                                   "fig07_forces_depth.png", out)
    rows = draft_table(runs)
    figures["drafts"] = plot_drafts(rows, out)
    with open(out / "drafts.csv", "w", newline="") as handle:
        keys = ["depth_m", "sokolovski", "nonpolar_fixed_floor", "nonpolar_coulomb_floor",
                "polar", "dem", "paper_nonpolar", "paper_polar", "experiment"]
        writer = csv.writer(handle)
        writer.writerow(keys)
        for r in rows:
            writer.writerow(["" if r.get(k) is None else "%.6g" % r[k] for k in keys])
    figures["stress"] = plot_blade_stress(pick("h0.35", "polar_h0.35", "polar_h0.35_free"), out)
    figures["dem_stress"], dem_stress = plot_dem_blade_stress(runs.get("dem_h0.35"),
                                                             runs.get("h0.35"), out)
    figures["pdr"] = plot_pdr(pick("h0.25", "polar_h0.25"), out, runs.get("dem_h0.25"))
    figures["yield"], bands = plot_yield_and_shear(pick("h0.25", "h0.25_coarse"), out)
    for name in figures.values():
        if name:
            print("wrote", out / name)
    write_report(out, runs, figures, rows, heights, bands, dem_stress, args)


def processor_seconds(path):
    """User + system time of a run's processes from bash `times` (its second line), or None."""
    if not path.exists():
        return None
    text = path.read_text().splitlines()
    if len(text) < 2:
        return None
    total = 0.0
    for minutes, seconds in re.findall(r"(\d+)m([\d.]+)s", text[1]):
        total += 60 * float(minutes) + float(seconds)
    return total


def write_report(out, runs, figures, rows, heights, bands, dem_stress, args):
    lines = ["# The paper's figures, reproduced", ""]
    lines.append("Made by `scripts/reproduce_paper.sh%s` (meshes %s and %s)."
                 % (" --quick" if args.quick else "", args.meshes[0], args.meshes[1]))
    if args.wall_seconds:
        lines.append("All runs took %.1f min of wall time." % (args.wall_seconds / 60))
    cpu = {name: processor_seconds(out / "runs" / (name + ".times")) for name in runs}
    for part, names in (("MPM", [n for n in runs if not isinstance(runs[n], DemRun)]),
                        ("DEM", [n for n in runs if isinstance(runs[n], DemRun)])):
        total_cpu = sum(cpu[n] for n in names if cpu[n] is not None)
        if total_cpu > 0:
            lines.append("The %s runs' processor time: %.1f min in all, so about %.1f min of "
                         "wall time for two runs at a time on an idle two-core machine."
                         % (part, total_cpu / 60, total_cpu / 120))

    def status_of(name):
        status_file = out / "runs" / (name + ".status")
        status, seconds = ("?", "?")
        if status_file.exists():
            status, seconds = status_file.read_text().split()
        log = out / "runs" / (name + ".log")
        error = ""
        if status not in ("0", "?") and log.exists():
            match = re.search(r"^error: (.*)$", log.read_text(), re.MULTILINE)
            error = match.group(1)[:160] if match else "exit %s" % status
        return ("complete" if status == "0" else "stopped: " + error.replace("|", "/"),
                seconds)

    lines += ["", "| run | arguments | reached | status | wall | processor |",
              "| --- | --- | ---: | --- | ---: | ---: |"]
    for name, run in runs.items():
        if isinstance(run, DemRun):
            continue
        status, seconds = status_of(name)
        shown = {"depth": None, "psi": None, "floor": None, "dilatancy-cutoff": "0", "flip": "1",
                 "polar": "false", "blade-rotation": "held", "blade-rotation-fixed": "true",
                 "separation": "false", "travel": None}
        arguments = " ".join("%s=%s" % (k, run.case[k]) for k, default in shown.items()
                             if k in run.case and run.case[k] != default)
        lines.append("| %s | %s, %s | %.0f mm | %s | %s s | %s s |" % (
            name, run.mesh, arguments, run.travel_reached * 1000, status, seconds,
            fmt(cpu[name], "%.0f")))
    dems = [name for name, run in runs.items() if isinstance(run, DemRun)]
    if dems:
        lines += ["", "| DEM run | h [mm] | grains | porosity | cutting steps | reached | status | "
                  "wall | processor |", "| --- | ---: | ---: | ---: | ---: | ---: | --- | ---: | "
                  "---: |"]
        for name in dems:
            run = runs[name]
            status, seconds = status_of(name)
            grains = run.packing["bodies"][0] if run.packing is not None else None
            porosity = run.packing["porosity"][0] if run.packing is not None else None
            lines.append("| %s | %.0f | %s | %s | %s | %.0f mm | %s | %s s | %s s |" % (
                name, run.depth * 1000, fmt(grains, "%.0f"), fmt(porosity, "%.3f"),
                fmt(run.value("cutting_steps"), "%.0f"), run.travel_reached * 1000, status,
                seconds, fmt(cpu[name], "%.0f")))
    statements = [
        ("flow", "Figs. 1-2", "the flow of corn in front of the blade at 100-400 mm of travel "
         "(h = 200 mm) by experiment, DEM and nonpolar MPM; nonpolar MPM with psi = 2 deg "
         "resembles the observed flow most closely."),
        ("surface", "Fig. 3", "with an increase in dilatancy angle there is an increase in "
         "material volumetric expansion: the free surface rises with psi."),
        ("psi", "Fig. 6", "over the first part of the displacement the responses are the same "
         "(elastic); in the plastic regions the blade forces increase with the dilatancy "
         "angle; the vertical force is negative; polar MPM is 13 % below nonpolar."),
        ("depth", "Fig. 7", "the forces increase with blade depth."),
        ("drafts", "Fig. 8", "nonpolar MPM overestimates Sokolovski by 12, 6 and 5 % at "
         "h = 150, 250 and 350 mm and underestimates the experiment by 25, 11 and 9 %; polar "
         "MPM is 28, 14 and 10 % below nonpolar; DEM is 6 % below to 12 % above the "
         "experiment."),
        ("stress", "Fig. 9", "nonpolar MPM blade stresses agree with Sokolovski; polar MPM "
         "predicts lower normal and shear stresses; free rotation at the blade leaves the "
         "normal stress and about halves the shear stress."),
        ("dem_stress", "Fig. 10", "the DEM blade stresses at h = 350 mm (the average force of "
         "two neighbouring contacts over their distance, averaged over 18-22 mm of travel) are "
         "lower than Sokolovski's but higher than the nonpolar MPM stresses."),
        ("pdr", "Fig. 11", "PDR >= 0.15 at 15 mm: the DEM slip line lies between the observed "
         "and Sokolovski lines at the surface and outside Sokolovski's near the blade's tip; the "
         "nonpolar slip line follows the observed and Sokolovski lines near the tip; polar MPM "
         "gives a straighter line at almost 45 deg."),
        ("yield", "Figs. 12-13", "yield points concentrate around the slip line, more and "
         "broader on the coarser mesh; J' shows a definite band that converges under mesh "
         "refinement."),
    ]
    for key, title, statement in statements:
        lines += ["", "## %s" % title, "", "The paper: %s" % statement, ""]
        if figures.get(key):
            lines.append("![%s](%s)" % (title, figures[key]))
        else:
            lines.append("(no figure: its runs are missing)")
        if key == "surface" and heights:
            lines += ["", "Highest point of the free surface ahead of the blade [mm]:", "",
                      "| psi | " + " | ".join("%.0f mm" % (t * 1000) for t in (0.1, 0.2, 0.3, 0.4))
                      + " |",
                      "| ---: |" + " ---: |" * 4]
            for psi in sorted({h[0] for h in heights}, key=float):
                cells = []
                for t in (0.1, 0.2, 0.3, 0.4):
                    value = [h[2] for h in heights if h[0] == psi and abs(h[1] - t) < 1e-9]
                    cells.append("%.0f" % (value[0] * 1000) if value else "-")
                lines.append("| %s | %s |" % (psi, " | ".join(cells)))
        if key in ("psi", "depth"):
            names = (("fig6_psi2", "fig6_psi10", "fig6_psi26", "polar_h0.35")
                     if key == "psi" else ("fig7_h0.15", "fig7_h0.25", "fig6_psi2"))
            windows = ((0.015, 0.035), (0.035, 0.05), (0.05, 0.1))
            lines += ["", "Average draft [N/m] over stretches of travel:", "",
                      "| run | " + " | ".join("%.0f-%.0f mm" % (a * 1000, b * 1000)
                                              for a, b in windows) + " |",
                      "| --- |" + " ---: |" * len(windows)]
            for name in names:
                if name not in runs or runs[name].forces is None:
                    continue
                forces = runs[name].forces
                cells = []
                for a, b in windows:
                    inside = ((forces["displacement_m"] >= a) & (forces["displacement_m"] <= b))
                    cells.append("%.0f" % forces["draft_N_per_m"][inside].mean()
                                 if inside.any() and forces["displacement_m"][-1] >= b - 1e-9
                                 else "-")
                lines.append("| %s | %s |" % (runs[name].label(), " | ".join(cells)))
        if key == "stress":
            lines += ["", "| run | normal stress, mean over the blade [kPa] | shear stress, mean "
                      "[kPa] | shear / normal |", "| --- | ---: | ---: | ---: |"]
            for name in ("h0.35", "polar_h0.35", "polar_h0.35_free"):
                folder = out / "runs" / name
                if not (folder / "blade_stress.csv").exists():
                    continue
                _, normal, shear = (v.mean() for v in mpm_blade_profile(folder))
                lines.append("| %s | %.2f | %.2f | %.3f |" % (runs[name].label(), normal, shear,
                                                             shear / normal))
        if key == "drafts":
            lines += ["", "| h [mm] | Sokolovski | ours, fixed floor | ours, Coulomb floor | "
                      "ours, polar | polar / nonpolar | ours, DEM | experiment (derived) |",
                      "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
            for r in rows:
                lines.append("| %.0f | %s | %s (%s) | %s (%s) | %s | %s | %s (%s; %s) | %s |" % (
                    r["depth_m"] * 1000, fmt(r["sokolovski"]), fmt(r["nonpolar_fixed_floor"]),
                    percent(r["nonpolar_fixed_floor"], r["sokolovski"]),
                    fmt(r["nonpolar_coulomb_floor"]),
                    percent(r["nonpolar_coulomb_floor"], r["sokolovski"]), fmt(r["polar"]),
                    percent(r["polar"], r["nonpolar_fixed_floor"]), fmt(r["dem"]),
                    percent(r["dem"], r["sokolovski"]), percent(r["dem"], r.get("experiment")),
                    fmt(r.get("experiment"))))
            lines += ["", "Drafts in N/m over 15-35 mm; percentages against Sokolovski "
                      "(polar: against our nonpolar, fixed floor; DEM: against Sokolovski and "
                      "the experiment). The experiment is derived: Sokolovski x (1.12, 1.06, "
                      "1.05) / (1 - 0.25, 0.11, 0.09)."]
        if key == "dem_stress" and dem_stress:
            lines += ["", "Mean over the blade's buried face [kPa]:", "",
                      "| | normal | shear |", "| --- | ---: | ---: |"]
            for who, label in (("dem", "DEM (neighbouring contacts)"),
                               ("sokolovski", "Sokolovski"), ("mpm", "our nonpolar MPM")):
                if who in dem_stress:
                    lines.append("| %s | %.2f | %.2f |" % (label, *dem_stress[who]))
        if key == "yield" and bands:
            lines += ["", "| mesh | share of particles in front of the blade at yield | J' band "
                      "width across the slip line at mid-depth [mm] |", "| --- | ---: | ---: |"]
            for mesh, n in bands.items():
                lines.append("| %s | %.2f | %s |" % (mesh, n["yield_fraction"],
                                                    fmt(None if n["band_width_m"] is None
                                                        else n["band_width_m"] * 1000, "%.0f")))
    (out / "report.md").write_text("\n".join(lines) + "\n")
    print("wrote", out / "report.md")


if __name__ == "__main__":
    main()
