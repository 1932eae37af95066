#!/usr/bin/python3
"""Region plot of a gaitopt impact map (thesis Figs. 2.3-2.16 kind).

Usage: scripts/plot/impact_map.py MAP_CSV|DIR [OUT_PNG | --out OUT_PNG] [--title TEXT]
(`gaitopt plot impact_map DIR --out OUT_PNG` calls it so.) MAP_CSV is the map.csv written by
`gaitopt impact-map` (theta_deg, mu, behaviour, n_solutions, status), or DIR/map.csv for its
output directory DIR. OUT_PNG defaults to map.png next to MAP_CSV. Each (theta, mu) sample is
a cell coloured by its behaviour (foot1/foot2 after the impact); indeterminate samples (several
solutions) are hatched and labelled with all their behaviours, inconsistent ones (no solution)
stay white. Exit 2 on a missing or malformed file.
Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib).
"""
import csv
import os
import sys

import numpy as np
from _common import fail as fail_kind
from _common import figure, out_as_positional, save

KIND = "impact_map"
COLUMNS = ["theta_deg", "mu", "behaviour", "n_solutions", "status"]


def fail(message):
    fail_kind(KIND, message)


def map_source(path):
    """The map.csv of an impact-map directory (or the CSV itself), or exit 2 naming what the
    directory is instead."""
    if not os.path.isdir(path):
        return path
    source = os.path.join(path, "map.csv")
    if not os.path.exists(source):
        for marker, what in (("summary.json", "a step run directory (summary.json)"),
                             ("sweep.csv", "a sweep directory (sweep.csv)"),
                             ("residuals.csv", "a diagnose directory (residuals.csv)")):
            if os.path.exists(os.path.join(path, marker)):
                fail(f"{path}: {what}, not an impact map; 'impact_map' needs the directory "
                     "written by gaitopt impact-map (map.csv) or its map.csv")
        fail(f"{path}: no map.csv: not a gaitopt impact-map directory")
    return source


def read_map(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
            header = rows and list(rows[0].keys())
    except (OSError, UnicodeDecodeError) as e:
        fail("cannot read %s: %s" % (path, e))
    if not rows or header != COLUMNS:
        fail("%s: expected the columns %s" % (path, ",".join(COLUMNS)))
    for i, r in enumerate(rows, start=2):
        try:
            r["theta_deg"], r["mu"] = float(r["theta_deg"]), float(r["mu"])
        except ValueError:
            fail("%s: row %d: theta_deg and mu must be numbers" % (path, i))
    return rows


def grid(rows):
    thetas = sorted({r["theta_deg"] for r in rows})
    mus = sorted({r["mu"] for r in rows})
    labels = sorted({r["behaviour"] for r in rows if r["behaviour"] != "none"})
    index = {label: k for k, label in enumerate(labels)}
    cells = np.full((len(mus), len(thetas)), np.nan)
    for r in rows:
        if r["behaviour"] != "none":
            cells[mus.index(r["mu"]), thetas.index(r["theta_deg"])] = index[r["behaviour"]]
    return np.array(thetas), np.array(mus), labels, cells


def edges(centres):
    if len(centres) == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])


def plot(rows, out, title):
    thetas, mus, labels, cells = grid(rows)
    fig, ax = figure(1, 1)
    from matplotlib.patches import Patch
    import matplotlib.pyplot as plt

    cmap = plt.get_cmap("tab20", max(len(labels), 1))
    ax.pcolormesh(edges(thetas), edges(mus), np.ma.masked_invalid(cells), cmap=cmap,
                  vmin=-0.5, vmax=len(labels) - 0.5, shading="flat")
    several = np.zeros_like(cells)
    for r in rows:
        if r["status"] == "indeterminate":
            several[list(mus).index(r["mu"]), list(thetas).index(r["theta_deg"])] = 1
    if several.any():
        ax.contourf(thetas, mus, several, levels=[0.5, 1.5], colors="none", hatches=["///"])
    handles = [Patch(facecolor=cmap(k), label=label) for k, label in enumerate(labels)]
    handles.append(Patch(facecolor="white", edgecolor="black", label="none (inconsistent)"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8,
              title="foot 1 / foot 2 (/// indeterminate)", title_fontsize=8)
    ax.set_xlabel(r"direction $\theta$ of $V_2^-$ [deg]  ($-90$ = vertical touchdown)")
    ax.set_ylabel(r"friction coefficient $\mu$")
    ax.set_title(title)
    save(KIND, fig, out)


def main(argv):
    title = "impact behaviour"
    if "--title" in argv:
        k = argv.index("--title")
        if k + 1 >= len(argv):
            fail("--title needs a value")
        title = argv[k + 1]
        argv = argv[:k] + argv[k + 2:]
    argv = out_as_positional(argv)
    if len(argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    source = map_source(argv[1])
    out = argv[2] if len(argv) == 3 else os.path.join(os.path.dirname(source) or ".", "map.png")
    if os.path.splitext(out)[1].lower() not in (".png", ".svg"):
        fail(f"--out {out}: the file name must end in .png or .svg")
    plot(read_map(source), out, title)


if __name__ == "__main__":
    main(sys.argv)
