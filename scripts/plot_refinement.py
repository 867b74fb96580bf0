#!/usr/bin/python3
"""The table and plot of scripts/refinement_study.sh.

usage: /usr/bin/python3 scripts/plot_refinement.py OUT [--earth-pressure EXAMPLE_02]

Reads OUT/runs/VARIANT_MESH_hDEPTH/summary.csv and writes OUT/refinement.md and
OUT/refinement.png: the 15-35 mm draft of each run against Sokolovski's (associated flow,
the reference of the paper) and against the Davis estimate of the non-associated soil's
collapse load: Sokolovski's solution at the reduced friction angle
tan(phi*) = sin(phi) cos(psi) / (1 - sin(phi) sin(psi)) (Davis 1968; Drescher and Detournay
1993), computed by example_02_earth_pressure when given.
"""
import argparse
import csv
import math
import pathlib
import re
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_flat_blade import read_csv  # noqa: E402

LABELS = {"linear": "bilinear, MUSL, FLIP (the paper's)", "fbar": "bilinear + F-bar",
          "apic": "quadratic B-spline + APIC"}


def case_of(folder):
    case = {}
    for line in (folder / "case.used").read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if "=" in line:
            key, value = (part.strip() for part in line.split("=", 1))
            case[key] = value
    return case


def davis_angle(phi_deg, psi_deg):
    phi, psi = math.radians(phi_deg), math.radians(psi_deg)
    return math.degrees(math.atan(math.sin(phi) * math.cos(psi) /
                                  (1 - math.sin(phi) * math.sin(psi))))


def davis_drafts(program, case, depths):
    """Sokolovski's passive force [N/m] at the Davis angle for each depth, or {}."""
    if not program:
        return {}
    phi_star = davis_angle(float(case["phi"]), float(case["psi"]))
    delta = min(float(case["delta"]), phi_star)
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([program, "--phi", "%.6f" % phi_star, "--delta", "%.6f" % delta,
                        "--gamma", "%.6f" % (float(case["density"]) * float(case["gravity"])),
                        "--height", ",".join("%g" % d for d in depths), "--out", folder],
                       check=True, stdout=subprocess.DEVNULL)
        summary = read_csv(pathlib.Path(folder) / "summary.csv")
    return {round(h, 6): f for h, f in zip(summary["height_m"],
                                          summary["horizontal_force_per_width_N_per_m"])}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--earth-pressure", help="example_02_earth_pressure, for Davis")
    args = parser.parse_args()
    results, stopped, case = [], [], None
    for folder in sorted((args.out / "runs").iterdir()):
        match = re.fullmatch(r"(\w+?)_(\d+)x(\d+)_h([\d.]+)", folder.name)
        if not folder.is_dir() or not match:
            continue
        if not (folder / "summary.csv").exists():
            stopped.append(folder.name)
            continue
        summary = read_csv(folder / "summary.csv")
        case = case or case_of(folder)
        results.append({"variant": match.group(1), "cells_x": int(match.group(2)),
                        "cells_y": int(match.group(3)), "depth": float(match.group(4)),
                        "draft": float(summary["average_draft_N_per_m"][0]),
                        "sokolovski": float(summary["sokolovski_draft_N_per_m"][0]),
                        "seconds": float(summary["run_seconds"][0]),
                        "strays": int(float(summary.get("stray_particles", [0])[0]))})
    if not results:
        raise SystemExit("plot_refinement.py: no finished runs in %s/runs" % args.out)
    depths = sorted({r["depth"] for r in results})
    davis = davis_drafts(args.earth_pressure, case, depths)
    phi_star = davis_angle(float(case["phi"]), float(case["psi"]))
    variants = [v for v in LABELS if any(r["variant"] == v for r in results)]

    fig, axes = plt.subplots(1, len(depths), figsize=(4.2 * len(depths), 4.2), sharey=True)
    for ax, depth in zip(axes, depths):
        for k, variant in enumerate(variants):
            rows = sorted((r for r in results if r["variant"] == variant and r["depth"] == depth),
                          key=lambda r: r["cells_x"])
            cell = [float(case["grid-length"]) / r["cells_x"] * 1000 for r in rows]
            ax.plot(cell, [100 * (r["draft"] / r["sokolovski"] - 1) for r in rows], "o-",
                    color="C%d" % k, label=LABELS[variant])
        ax.axhline(0, color="k", lw=1, label="Sokolovski (associated)")
        ax.axhspan(-5, 5, color="0.92", zorder=0, label="within 5 %")
        if round(depth, 6) in davis:
            reference = [r["sokolovski"] for r in results if r["depth"] == depth][0]
            ax.axhline(100 * (davis[round(depth, 6)] / reference - 1), color="C3", ls="--",
                       label="Davis, phi* = %.2f deg" % phi_star)
        ax.set_title("h = %.0f mm" % (depth * 1000))
        ax.set_xlabel("cell size [mm]")
        ax.invert_xaxis()
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("draft 15-35 mm against Sokolovski [%]")
    axes[0].legend(fontsize=7)
    fig.suptitle("Flat blade under mesh refinement (floor: %s)" % case["floor"])
    fig.tight_layout()
    fig.savefig(args.out / "refinement.png", dpi=100)
    plt.close(fig)

    lines = ["# Flat blade under refinement (floor: %s, psi = %s deg)" % (case["floor"],
                                                                          case["psi"]), "",
             "Drafts over 15-35 mm in N/m; in brackets against Sokolovski (associated flow)%s."
             % (" and against the Davis estimate (phi* = %.2f deg)" % phi_star if davis else ""),
             ""]
    header = "| variant | mesh | " + " | ".join("h = %.0f mm" % (d * 1000) for d in depths)
    lines += [header + " | run time [s] |", "| --- | --- |" + " ---: |" * (len(depths) + 1)]
    for variant in variants:
        for cells in sorted({r["cells_x"] for r in results if r["variant"] == variant}):
            rows = {r["depth"]: r for r in results
                    if r["variant"] == variant and r["cells_x"] == cells}
            cells_text = []
            for d in depths:
                r = rows.get(d)
                if r is None:
                    cells_text.append("-")
                    continue
                text = "%.1f (%+.1f %%" % (r["draft"], 100 * (r["draft"] / r["sokolovski"] - 1))
                if round(d, 6) in davis:
                    text += "; %+.1f %%" % (100 * (r["draft"] / davis[round(d, 6)] - 1))
                if r["strays"]:
                    text += "; %d point%s left the rig" % (r["strays"], "s" * (r["strays"] > 1))
                cells_text.append(text + ")")
            any_row = next(iter(rows.values()))
            lines.append("| %s | %dx%d | %s | %.0f |" % (
                variant, cells, any_row["cells_y"], " | ".join(cells_text),
                sum(r["seconds"] for r in rows.values())))
    if davis:
        lines += ["", "Sokolovski: " + ", ".join(
            "%.1f" % [r["sokolovski"] for r in results if r["depth"] == d][0] for d in depths) +
            " N/m; Davis: " + ", ".join("%.1f" % davis[round(d, 6)] for d in depths) + " N/m."]
    if stopped:
        lines += ["", "Stopped before the average was complete: " + ", ".join(stopped) + "."]
    (args.out / "refinement.md").write_text("\n".join(lines) + "\n")
    print("wrote", args.out / "refinement.md", "and", args.out / "refinement.png")


if __name__ == "__main__":
    main()
