#!/usr/bin/python3
"""Rocker-foot figure of the report.json of `gaitopt import-opensim --result DIR`.

Usage: scripts/plot/opensim_rocker.py REPORT.json [OUT.png]   (default: REPORT.png)

Left: centre-of-pressure travel against the stance-shank angle alpha, one curve per stance
(CoP and alpha centred on each stance's force-weighted means), with the fitted rocker lines
(slope -r) and the roll-over-shape literature value (0.3 x leg length). A point foot would be
a horizontal line. Right: the same travel against time within the stance.
Needs the Debian packages python3-numpy and python3-matplotlib.
"""
import json
import os
import sys

import numpy as np
from _common import fail, figure, out_as_positional, save

KIND = "opensim_rocker"


def centred(values, weights):
    return values - np.average(values, weights=weights)


def main():
    argv = out_as_positional(sys.argv)
    if len(argv) not in (2, 3):
        sys.exit(__doc__)
    report_path = argv[1]
    if os.path.isdir(report_path):
        fail(KIND, f"{report_path}: a directory, not an import-opensim report; 'opensim_rocker' "
                   "needs the report.json written by gaitopt import-opensim --result")
    out = argv[2] if len(argv) == 3 else report_path.rsplit(".", 1)[0] + ".png"
    if os.path.splitext(out)[1].lower() not in (".png", ".svg"):
        fail(KIND, f"--out {out}: the file name must end in .png or .svg")
    try:
        with open(report_path) as f:
            report = json.load(f)
        rocker = report["rocker_foot"]
    except (OSError, ValueError) as e:
        fail(KIND, f"cannot read {report_path}: {e}")
    except (KeyError, TypeError):
        fail(KIND, f"{report_path}: no 'rocker_foot' member: not the report.json of "
                   "gaitopt import-opensim")
    fig, (ax_a, ax_t) = figure(1, 2)
    colours = {"right": "tab:red", "left": "tab:blue"}
    span = np.array([-0.45, 0.45])
    for stance in report["stances"]:
        w = np.array(stance["vertical_force"])
        a = centred(np.array(stance["shank"]), w)
        c = centred(np.array(stance["cop_x"]), w)
        ax_a.plot(np.degrees(a), c, color=colours[stance["side"]], alpha=0.7)
        ax_t.plot(np.arange(len(c)) / 120.0, c, color=colours[stance["side"]], alpha=0.7)
    for name, r, style in (("fit, all stances", rocker["radius_all"], "k-"),
                           ("0.3 x leg length", rocker["literature_radius"], "k--")):
        ax_a.plot(np.degrees(span), -r * span, style, label="%s: r = %.3f m" % (name, r))
    ax_a.axhline(0.0, color="grey", lw=0.8, label="point foot")
    ax_a.set_xlabel("stance-shank angle alpha - mean [deg]")
    ax_a.set_ylabel("CoP x - mean [m]")
    ax_a.set_title("CoP travel vs shank rotation (red right, blue left)")
    ax_a.legend(fontsize=8)
    ax_t.set_xlabel("time in stance [s]")
    ax_t.set_ylabel("CoP x - mean [m]")
    ax_t.set_title("held-out CoP RMS: point %.1f mm, rocker %.1f mm" % (
        1e3 * rocker["holdout_cop_rms_point_foot"], 1e3 * rocker["holdout_cop_rms_rocker"]))
    save(KIND, fig, out)


if __name__ == "__main__":
    main()
