#!/usr/bin/python3
"""Plot a gaitopt sweep: C_Gamma, C_E, W and C_frott against the walking speed.

Usage: scripts/plot_sweep.py SWEEP_CSV [OUT_PNG]
OUT_PNG defaults to sweep.png next to SWEEP_CSV. Speeds whose status is not "optimal" are
drawn as open red markers; empty fields (criteria not computed) are left out.
Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PANELS = [
    ("C_Gamma", r"$C_\Gamma$ [N$^2$$\cdot$m$\cdot$s]", "torque criterion per metre (3.28)"),
    ("C_E", r"$C_E$ [J/m]", "electrical energy per metre (3.32)"),
    ("W", r"$W$ [J/m]", "absolute motor work per metre (3.147)"),
    ("C_frott", r"$C_{frott}$ [J/m]", "net motor work per metre (3.148)"),
]


def number(text):
    return float(text) if text.strip() else np.nan


def main(argv):
    if len(argv) not in (2, 3):
        sys.stderr.write(__doc__)
        return 2
    path = argv[1]
    out = argv[2] if len(argv) == 3 else os.path.join(os.path.dirname(path) or ".", "sweep.png")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.stderr.write(f"plot_sweep: {path}: no rows\n")
        return 2
    missing = [k for k, _, _ in PANELS if k not in rows[0]] + (["speed"] if "speed" not in rows[0] else [])
    if missing:
        sys.stderr.write(f"plot_sweep: {path}: missing columns {', '.join(missing)}\n")
        return 2
    rows.sort(key=lambda r: float(r["speed"]))
    speed = np.array([float(r["speed"]) for r in rows])
    optimal = np.array([r["status"] == "optimal" for r in rows])

    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), sharex=True)
    for ax, (key, label, title) in zip(axes.flat, PANELS):
        y = np.array([number(r[key]) for r in rows])
        ax.plot(speed[optimal], y[optimal], "o-", color="C0", label="optimal")
        if (~optimal).any():
            ax.plot(speed[~optimal], y[~optimal], "o", mfc="none", color="C3", label="not optimal")
            ax.legend(fontsize="small")
        ax.set_ylabel(label)
        ax.set_title(title, fontsize="medium")
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("walking speed [m/s]")
    fig.suptitle(f"gaitopt sweep: {path}", fontsize="medium")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"plot_sweep: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
