#!/usr/bin/python3
"""Plot the output of example_04_granular_collapse (one run directory, or several to compare).

usage: /usr/bin/python3 scripts/plot_granular_collapse.py RUN_DIR [RUN_DIR ...] [--output DIR]
                                                          [--labels A,B,...]

Writes into the first RUN_DIR (or --output):
  deposit.png  the final deposit of the first run (particles coloured by their initial layer,
               from the last ParaView frame when there is one) and the surface of every run,
               against the experiment's final height at the wall and runout (the true-2D rod
               collapses of arXiv:1512.05180) and the initial column
  energy.png   potential energy released, kinetic energy from the grid and from the particles
               against time, linear and logarithmic, with the rest threshold
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from plot_flat_blade import read_csv  # noqa: E402  (same folder)


def read_summary(path):
    values = {}
    with open(path) as handle:
        for line in handle:
            if " = " in line:
                key, value = line.rstrip("\n").split(" = ", 1)
                values[key] = value
    return values


def label_of(summary):
    transfer = "APIC" if summary.get("transfer") == "apic" else "FLIP " + summary["flip"]
    return "%s, %s, %g mm, %s ppc, %s, %s floor" % (
        summary["shape"], summary["scheme"].upper(), float(summary["cell_m"]) * 1e3,
        summary["ppc"], transfer, summary["floor"])


def last_frame(run):
    frames = sorted((run / "frames").glob("collapse_*.h5"))
    if not frames:
        return None
    import h5py  # only needed for the particle picture

    with h5py.File(frames[-1], "r") as handle:
        # Frame format 2 keeps the particles in a group, positions as x, y, z.
        group = handle["particles"] if "particles" in handle else handle
        return {"position": group["position"][...][:, :2],
                "initial_position": group["initial_position"][...][:, :2],
                "volume": group["volume"][...], "time": handle.attrs["time"]}


def plot_deposit(runs, labels, output):
    first = read_summary(runs[0] / "summary.txt")
    h0, d0 = float(first["column_height_m"]), float(first["column_width_m"])
    height = float(first["reference_final_height_m"])
    runout_power = float(first["reference_runout_power_m"])
    runout_linear = float(first["reference_runout_linear_m"])
    fig, ax = plt.subplots(figsize=(11, 3.4))
    frame = last_frame(runs[0])
    if frame is not None:
        # Layers of h0 / 5 from the initial positions, as in the paper's coloured flow patterns.
        layer = np.floor(frame["initial_position"][:, 1] / (0.2 * h0)).astype(int)
        palette = np.array(["#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1"])
        ax.scatter(frame["position"][:, 0], frame["position"][:, 1], c=palette[layer % 5], s=1.5,
                   linewidths=0, rasterized=True,
                   label="particles at t = %.2f s (layers of h0/5)" % frame["time"])
    for run, label in zip(runs, labels):
        profile = read_csv(run / "profile.csv")
        occupied = profile["particles"] > 0
        x = np.concatenate(([0.0], profile["x_m"][occupied]))
        y = np.concatenate(([profile["surface_m"][occupied][0]], profile["surface_m"][occupied]))
        summary = read_summary(run / "summary.txt")
        line, = ax.plot(x, y, lw=1.2, label="%s: runout %.3f m" % (
            label, float(summary["deposit_front_m"])))
        ax.plot([float(summary["deposit_front_m"])] * 2, [-0.004, 0.004], color=line.get_color(),
                lw=2)
    ax.plot([0, d0, d0], [h0, h0, 0], "k--", lw=1, label="initial column, a = h0/d0 = %.2g" %
            (h0 / d0))
    ax.plot([0.0], [height], "kD", ms=8,
            label="experiment: final height h0 / (1.42 a^(2/3)) = %.4f m" % height)
    ax.errorbar([0.5 * (runout_power + runout_linear)], [0.0],
                xerr=[[0.5 * abs(runout_power - runout_linear)]], fmt="k^", ms=9, capsize=4,
                label="experiment: runout %.3f-%.3f m (two fits)" % (
                    min(runout_power, runout_linear), max(runout_power, runout_linear)))
    wall = float(first.get("wall_m", "0"))
    if wall > 0.0:  # example 04 --wall: the fixed rigid wall, 4 cells thick
        ax.add_patch(matplotlib.patches.Rectangle(
            (wall, -0.005), 4.0 * float(first["cell_m"]), 1.2 * h0, color="0.6",
            label="fixed wall, mu = %s: the soil pushes it with %.1f N/m" % (
                first["wall_friction"], float(first["wall_force_x_N_per_m"]))))
    ax.set_xlabel("x (m), from the wall")
    ax.set_ylabel("y (m)")
    ax.set_xlim(0, max(0.6, 1.15 * runout_power))
    ax.set_ylim(-0.005, 1.15 * h0)
    ax.set_aspect("equal")
    ax.set_title("Granular collapse to rest against the true-2D aluminium-rod collapses of "
                 "arXiv:1512.05180")
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(output / "deposit.png", dpi=150)
    plt.close(fig)


def plot_energy(runs, labels, output):
    fig, (linear, log) = plt.subplots(1, 2, figsize=(12, 4.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, (run, label) in enumerate(zip(runs, labels)):
        series = read_csv(run / "series.csv")
        summary = read_summary(run / "summary.txt")
        colour = colours[k % len(colours)]
        t = series["time_s"]
        if k == 0:
            linear.plot(t, series["potential_released_J_per_m"], color="0.4", lw=1.2,
                        label="potential energy released: " + label)
        linear.plot(t, series["grid_kinetic_J_per_m"], color=colour, lw=1.4,
                    label="kinetic, grid: " + label)
        linear.plot(t, series["particle_kinetic_J_per_m"], color=colour, lw=1.0, ls="--",
                    label="kinetic, particles")
        log.semilogy(t, np.maximum(series["grid_kinetic_J_per_m"], 1e-12), color=colour, lw=1.4,
                     label="grid: " + label)
        log.semilogy(t, np.maximum(series["particle_kinetic_J_per_m"], 1e-12), color=colour,
                     lw=1.0, ls="--", label="particles")
        if k == 0:
            scale = float(summary["energy_scale_J_per_m"])
            log.axhline(1e-6 * scale, color="k", lw=0.8, ls=":",
                        label="rest threshold 1e-6 m g h0/2")
            log.set_ylim(1e-9 * scale, 2 * scale)
    linear.set_xlabel("time (s)")
    linear.set_ylabel("energy (J/m)")
    linear.legend(fontsize=7)
    linear.set_title("Energy history")
    log.set_xlabel("time (s)")
    log.set_ylabel("kinetic energy (J/m)")
    log.set_title("Kinetic energy: grid (solid) and particles (dashed)")
    log.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(output / "energy.png", dpi=150)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", type=pathlib.Path)
    parser.add_argument("--output", type=pathlib.Path)
    parser.add_argument("--labels", help="comma-separated legend labels, one per run")
    args = parser.parse_args()
    output = args.output or args.runs[0]
    output.mkdir(parents=True, exist_ok=True)
    if args.labels:
        labels = args.labels.split(",")
    else:
        labels = [label_of(read_summary(run / "summary.txt")) for run in args.runs]
    plot_deposit(args.runs, labels, output)
    plot_energy(args.runs, labels, output)
    print("wrote %s and %s" % (output / "deposit.png", output / "energy.png"))


if __name__ == "__main__":
    main()
