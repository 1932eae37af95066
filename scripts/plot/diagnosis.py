#!/usr/bin/python3
"""Plot the residuals of `gaitopt diagnose` before and after the identified effects.

Usage: scripts/plot/diagnosis.py OUT_DIR [OUT_PNG]
Reads OUT_DIR/residuals.csv (one row per sample; <channel>_nominal and <channel>_extended
columns, empty where a channel has no value) and writes one panel per channel with data:
residual against time, nominal model in grey, extended model in colour, held-out steps shaded.
OUT_PNG defaults to OUT_DIR/diagnosis.png.
Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from _common import out_as_positional  # noqa: E402

UNITS = {"alpha_row": "N·m", "R1x": "N", "R1z": "N", "R2x": "N", "R2z": "N", "ds_foot2_z": "m"}


def number(text):
    return float(text) if text.strip() else np.nan


def main(argv):
    argv = out_as_positional(argv)
    if len(argv) not in (2, 3):
        sys.exit(__doc__)
    out_dir = argv[1]
    png = argv[2] if len(argv) == 3 else os.path.join(out_dir, "diagnosis.png")
    with open(os.path.join(out_dir, "residuals.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("residuals.csv has no rows")
    t = np.array([float(r["t"]) for r in rows])
    held = np.array([r["heldout"] == "1" for r in rows])
    channels = [c[: -len("_nominal")] for c in rows[0] if c.endswith("_nominal")]
    data = {}
    for c in channels:
        before = np.array([number(r[c + "_nominal"]) for r in rows])
        after = np.array([number(r[c + "_extended"]) for r in rows])
        if np.isfinite(before).any():
            data[c] = (before, after)
    fig, axes = plt.subplots(len(data), 1, figsize=(11, 1.9 * len(data)), sharex=True, squeeze=False)
    for ax, (c, (before, after)) in zip(axes[:, 0], data.items()):
        ax.fill_between(t, 0, 1, where=held, color="0.92", transform=ax.get_xaxis_transform(), lw=0)
        ax.plot(t, before, ".", ms=1, color="0.55", label="nominal")
        ax.plot(t, after, ".", ms=1, color="tab:blue", label="extended")
        ax.set_ylabel(f"{c}\n[{UNITS.get(c, 'N·m')}]", fontsize=8)
        ax.axhline(0.0, color="k", lw=0.5)
        # Robust limits: a few samples at phase ends (one-sided smoothing) would flatten the rest.
        finite = np.concatenate([before[np.isfinite(before)], after[np.isfinite(after)]])
        lo, hi = np.percentile(finite, [1, 99])
        pad = 0.15 * (hi - lo) if hi > lo else 1e-9
        ax.set_ylim(lo - pad, hi + pad)
    axes[0, 0].legend(loc="upper right", markerscale=8, fontsize=8)
    axes[0, 0].set_title("measured − predicted (held-out steps shaded)")
    axes[-1, 0].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(png)


if __name__ == "__main__":
    main(sys.argv)
