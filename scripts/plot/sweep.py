#!/usr/bin/python3
"""gaitopt plot sweep RUN_DIR [--out FILE]: a speed sweep — the criteria C_Γ, C_E (with the
cost of transport on its right axis), W and C_frott, the step length and the phase durations
against the walking speed (thesis Fig. 3.19–3.26).

Reads RUN_DIR/sweep.csv (gaitopt sweep or sweep-merge) and, for the criterion the sweep
minimised, the summary.json of its speed folders (the title names it and its panel says
"minimised"). Speeds whose status is not "optimal" are drawn as open red markers; empty fields
(values not computed) are left out.
"""
import glob
import json
import os
import sys

import numpy as np

import _common as c

KIND = "sweep"
PANELS = [
    (["C_Gamma"], r"$C_\Gamma$ [N$^2\cdot$m$\cdot$s]", "torque criterion per metre (3.28)"),
    (["C_E"], r"$C_E$ [J/m]", "electrical energy per metre (3.32)"),
    (["W"], r"$W$ [J/m]", "absolute motor work per metre (3.147)"),
    (["C_frott"], r"$C_{frott}$ [J/m]", "net motor work per metre (3.148)"),
    (["step_length"], "step length d [m]", "step length"),
    (["T_SS", "T_DS"], "duration [s]", "single- and double-support durations"),
]


def minimised_criterion(run_dir):
    """The criterion of the sweep's optimisations (summary.json of a speed folder), or None."""
    for path in sorted(glob.glob(os.path.join(run_dir, "v*", "summary.json"))):
        try:
            with open(path) as f:
                criterion = json.load(f).get("criterion")
        except (OSError, ValueError):
            continue
        if criterion:
            return criterion
    return None


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    rows = c.sweep_run(KIND, run_dir)
    c.require_columns(KIND, f"{run_dir}/sweep.csv", rows,
                      ["speed", "status"] + [k for keys, _, _ in PANELS for k in keys])
    speed = rows["speed"]
    optimal = rows["status"] == "optimal"
    criterion = minimised_criterion(run_dir)
    fig, axes = c.figure(2, 3, sharex=True)
    for ax, (keys, label, title) in zip(axes.flat, PANELS):
        if criterion in keys:
            title += " — minimised"
        for k, key in enumerate(keys):
            y = rows[key]
            name = f"{key}, optimal" if len(keys) > 1 else "optimal"
            ax.plot(speed[optimal], y[optimal], "o-", color=f"C{k}", ms=4, label=name)
            if (~optimal).any():
                ax.plot(speed[~optimal], y[~optimal], "o", mfc="none", color="C3", label="not optimal" if k == 0 else None)
        if len(keys) > 1 or (~optimal).any():
            ax.legend(fontsize="small")
        ax.set_ylabel(label)
        ax.set_title(title, fontsize="medium")
        ax.grid(True, alpha=0.3)
        if keys == ["C_E"] and "CoT" in rows:  # the same curve in units of the robot's weight
            cot = ax.twinx()
            lo, hi = ax.get_ylim()
            ratio = np.nanmedian(rows["CoT"] / rows["C_E"])
            cot.set_ylim(lo * ratio, hi * ratio)
            cot.set_ylabel("cost of transport C_E/(m g)")
    for ax in axes[1]:
        ax.set_xlabel("walking speed [m/s]")
    count = f"{np.count_nonzero(optimal)}/{speed.size} speeds optimal"
    goal = f"minimising {criterion}" if criterion else "criterion not recorded"
    fig.suptitle(f"Speed sweep, {goal} ({count})\n{run_dir}", fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
