#!/usr/bin/python3
"""Residuals of `gaitopt diagnose` before and after the identified effects.

Usage: gaitopt plot diagnosis DIAG_DIR [--out FILE.png|FILE.svg]
   or: scripts/plot/diagnosis.py DIAG_DIR [--out FILE]       (default DIAG_DIR/diagnosis.png)
Reads DIAG_DIR/residuals.csv (one row per sample; <channel>_nominal and <channel>_extended
columns, empty where a channel has no value) and draws one panel per channel with data:
residual against time, nominal model in grey, extended model in colour, held-out steps shaded;
the title is the first cause of DIAG_DIR/diagnosis.json. A directory of another kind is exit 2.
Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib).
"""
import json
import os
import sys

import numpy as np
from _common import fail, figure, parse_args, read_csv, save

KIND = "diagnosis"
UNITS = {"alpha_row": "N·m", "R1x": "N", "R1z": "N", "R2x": "N", "R2z": "N", "ds_foot2_z": "m", "cop1x": "m"}


def diagnosis_run(run_dir):
    """(diagnosis.json dict, residuals.csv columns) of a diagnose directory, or exit 2."""
    path = os.path.join(run_dir, "residuals.csv")
    if not os.path.exists(path):
        for marker, what in (("summary.json", "a step run directory (summary.json)"),
                             ("sweep.csv", "a sweep directory (sweep.csv)")):
            if os.path.exists(os.path.join(run_dir, marker)):
                fail(KIND, f"{run_dir}: {what}, not a diagnosis; 'diagnosis' needs the directory "
                           "written by gaitopt diagnose (residuals.csv, diagnosis.json)")
        fail(KIND, f"{run_dir}: no residuals.csv: not a gaitopt diagnose directory")
    try:
        with open(os.path.join(run_dir, "diagnosis.json")) as f:
            diagnosis = json.load(f)
    except (OSError, ValueError) as e:
        fail(KIND, f"{run_dir}: cannot read diagnosis.json ({e})")
    return diagnosis, read_csv(KIND, path)


def cause_text(diagnosis):
    causes = diagnosis.get("cause") or []
    if not causes:
        return "no cause found"
    return "causes: " + ", ".join(
        f"{c.get('effect', '?')}@{c.get('joint', '-')}" for c in causes)


def main(argv):
    run_dir, out = parse_args(KIND, __doc__.splitlines()[0], argv[1:])
    diagnosis, res = diagnosis_run(run_dir)
    channels = [c[: -len("_nominal")] for c in res if c.endswith("_nominal")]
    data = {c: (res[c + "_nominal"], res[c + "_extended"]) for c in channels
            if np.isfinite(res[c + "_nominal"]).any()}
    if not data:
        fail(KIND, f"{run_dir}/residuals.csv: no channel has data")
    fig, axes = figure(len(data), 1, sharex=True, squeeze=False)
    held = res["heldout"] == 1
    for ax, (c, (before, after)) in zip(axes[:, 0], data.items()):
        ax.fill_between(res["t"], 0, 1, where=held, color="0.92", transform=ax.get_xaxis_transform(), lw=0)
        ax.plot(res["t"], before, ".", ms=1, color="0.55", label="nominal")
        ax.plot(res["t"], after, ".", ms=0.5, color="tab:blue", label="extended")
        ax.set_ylabel(f"{c.replace('gamma_', '')}\n[{UNITS.get(c, 'N·m')}]", fontsize=7)
        ax.axhline(0.0, color="k", lw=0.5)
        # Robust limits: the samples at phase ends (one-sided smoothing, impacts) would flatten
        # the rest, where an effect shows as an offset between the grey and the blue.
        finite = np.concatenate([before[np.isfinite(before)], after[np.isfinite(after)]])
        lo, hi = np.percentile(finite, [5, 95])
        pad = 0.5 * (hi - lo) if hi > lo else 1e-9
        ax.set_ylim(lo - pad, hi + pad)
    axes[0, 0].legend(loc="upper right", markerscale=8, fontsize=8)
    axes[0, 0].set_title(f"measured − predicted (held-out steps shaded); {cause_text(diagnosis)}")
    axes[-1, 0].set_xlabel("t [s]")
    save(KIND, fig, out)


if __name__ == "__main__":
    main(sys.argv)
