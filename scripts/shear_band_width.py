#!/usr/bin/python3
"""Shear-band width of a flat-blade run, from the frame closest to a given blade travel.

usage: /usr/bin/python3 scripts/shear_band_width.py RUN_DIR [RUN_DIR ...] [--travel 0.015]

The band is taken as the particles whose indicator is at least half the largest value in a
horizontal strip (in the rig's axes when it was turned against the grid, --rig-angle): the
Cosserat rotation |omega| for polar runs (the paper's Fig. 14), the shear-strain intensity J' since the blade started for nonpolar runs (Fig. 13). In strips at
1/3 and 2/3 of the depth the band's horizontal extent and centre are measured; the centres
give the band's inclination theta to the horizontal, and the width normal to the band is the
horizontal extent times sin(theta).
"""
import argparse
import csv
import math
import pathlib

import numpy as np

from plot_flat_blade import in_rig_axes, nearest_frame, read_frame  # same folder


def summary_of(run):
    with open(run / "summary.csv", newline="") as handle:
        return {k: float(v) for k, v in next(csv.DictReader(handle)).items()}


def frame_at(run, start, speed, travel):
    frames = sorted((run / "frames").glob("flat_blade_*.h5"))
    best, best_travel = nearest_frame(frames, start, speed, travel)
    return frames[0], best, best_travel


def measure(run, travel):
    s = summary_of(run)
    first, path, at = frame_at(run, s["cutting_start_s"], s["blade_speed_m_per_s"], travel)
    start, frame = read_frame(first), read_frame(path)
    x = in_rig_axes(s, frame["position"])
    if frame["micro_rotation"] is not None:
        indicator = np.abs(frame["micro_rotation"])
        name = "|rotation|"
    else:
        exx = frame["strain_xx"] - start["strain_xx"]
        eyy = frame["strain_yy"] - start["strain_yy"]
        exy = frame["strain_xy"] - start["strain_xy"]
        indicator = ((exx - eyy) ** 2 + eyy ** 2 + exx ** 2) / 6 + exy ** 2
        name = "J'"
    depth = s["depth_m"]
    face = s["blade_face_x_m"] + at
    rows = []
    for fraction in (1.0 / 3.0, 2.0 / 3.0):
        y = depth * fraction
        strip = (np.abs(x[:, 1] - y) < 0.05 * depth) & (x[:, 0] > face + 0.01)
        values, xs = indicator[strip], x[strip, 0]
        band = values >= 0.5 * values.max()
        rows.append((y, xs[band].min(), xs[band].max(), np.average(xs[band], weights=values[band])))
    (y1, a1, b1, c1), (y2, a2, b2, c2) = rows
    theta = math.atan2(y2 - y1, c2 - c1)
    widths = [(b - a) * math.sin(theta) for (_, a, b, _) in rows]
    return name, at, math.degrees(theta), widths


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", type=pathlib.Path)
    parser.add_argument("--travel", type=float, default=0.015)
    args = parser.parse_args()
    print("| run | indicator | travel [mm] | band inclination [deg] | width at h/3 [mm] | "
          "width at 2h/3 [mm] |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for run in args.runs:
        name, at, theta, widths = measure(run, args.travel)
        print("| %s | %s | %.1f | %.0f | %.0f | %.0f |" % (run.name, name, at * 1000, theta,
                                                            widths[0] * 1000, widths[1] * 1000))


if __name__ == "__main__":
    main()
