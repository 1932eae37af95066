#!/usr/bin/python3
"""gaitopt plot zero_dynamics RUN_DIR [--out FILE]: the Poincaré maps of the zero dynamics
(thesis §4.2.2) of `gaitopt stability`: Fig. 4.5 — the SS-plus-touchdown map a: α̇_fDS = α̇_iSS →
α̇_iDS (closed loop, and (4.28)) between the two bound curves of the time-optimal DS law (the
fastest and slowest α̇_iDS that reach the DS end at α̇_fDS, integrated with α̈_max and α̈_min),
the map of α̇_iDS (Fig. 4.6) and of α̇_iSS (Fig. 4.7) with the identity, the fixed point and the
regions of attraction in one step and within the study's step limit.

Reads RUN_DIR/zero_dynamics_map.csv (alphad_iSS, alphad_iDS, next_alphad_iSS, next_alphad_iDS,
steps_to_cycle, outcome), RUN_DIR/stability.json (zero_dynamics) and, when the gait has a double
support, RUN_DIR/ds_bounds.csv (alphad_fDS, alphad_iDS_braking, alphad_iDS_speeding_up, a,
cycle_exists, ...). Like the thesis, the axes show −α̇ [rad/s] (positive when walking forward).
Starts that fall are marked with crosses.
"""
import json
import os
import sys

import numpy as np

import _common as c

KIND = "zero_dynamics"
COLUMNS = ["alphad_iSS", "alphad_iDS", "next_alphad_iSS", "next_alphad_iDS", "steps_to_cycle", "outcome"]
BOUND_COLUMNS = ["alphad_fDS", "alphad_iDS_braking", "alphad_iDS_speeding_up", "a", "cycle_exists"]


def stability_run(run_dir):
    map_path = os.path.join(run_dir, "zero_dynamics_map.csv")
    json_path = os.path.join(run_dir, "stability.json")
    if not os.path.exists(map_path):
        if os.path.exists(os.path.join(run_dir, "summary.json")):
            c.fail(KIND, f"{run_dir}: a step run directory (summary.json), not a stability run; "
                         "'zero_dynamics' needs the directory written by gaitopt stability")
        if os.path.exists(os.path.join(run_dir, "sweep.csv")):
            c.fail(KIND, f"{run_dir}: a sweep directory (sweep.csv), not a stability run; "
                         "'zero_dynamics' needs the directory written by gaitopt stability")
        c.fail(KIND, f"{run_dir}: no zero_dynamics_map.csv: not a gaitopt stability directory")
    table = c.read_csv(KIND, map_path, key="alphad_iSS")
    c.require_columns(KIND, map_path, table, COLUMNS)
    try:
        with open(json_path) as f:
            study = json.load(f)["zero_dynamics"]
    except (OSError, ValueError, KeyError) as e:
        c.fail(KIND, f"{json_path}: no zero_dynamics object ({e})")
    return table, study


def ds_bounds(run_dir):
    """The Fig. 4.5 table, or None for a gait without double support (no ds_bounds.csv)."""
    path = os.path.join(run_dir, "ds_bounds.csv")
    if not os.path.exists(path):
        return None
    table = c.read_csv(KIND, path, key="alphad_fDS")
    c.require_columns(KIND, path, table, BOUND_COLUMNS)
    return table


def bound_curves(ax, bounds):
    """Fig. 4.5: between the curves, the DS starts that reach (alpha_fDS, alphad_fDS)."""
    x = -bounds["alphad_fDS"]
    fast, slow = -bounds["alphad_iDS_braking"], -bounds["alphad_iDS_speeding_up"]
    ax.fill_between(x, slow, fast, where=np.isfinite(fast) & np.isfinite(slow), color="#fde8c8",
                    zorder=0, label=r"$S_d$ at $\alpha_{iDS}$ (reaches the DS end)")
    ax.plot(x, fast, "-", color="C3", lw=1.5, label=r"braking ($\ddot\alpha_{max}$): fastest start")
    ax.plot(x, slow, "-", color="C0", lw=1.5, label=r"speeding up ($\ddot\alpha_{min}$): slowest start")
    ax.plot(x, -bounds["a"], ":", color="k", lw=1.5, label="a by (4.28)")
    exists = bounds["cycle_exists"] > 0.5
    if exists.any():
        ax.plot(x[exists], -bounds["a"][exists], "|", color="C2", ms=8, label="cyclic motion exists (Th. 3)")


def shade(ax, study):
    for key, colour, label in (("global_region", "0.92", "converges within %d steps" % study["global_max_steps"]),
                               ("one_step_region", "#cfe8cf", "converges in one step")):
        low, high = study[key]
        if low is not None and high is not None:
            ax.axvspan(-high, -low, color=colour, zorder=0, label=label)


def map_panel(ax, x, y, failed, title, name, study=None, identity=True):
    """The map y(x); failed starts as crosses on the curve, or at its foot when y is missing."""
    if study is not None:
        shade(ax, study)
    ok = np.isfinite(x) & np.isfinite(y)
    ax.plot(-x[ok & ~failed], -y[ok & ~failed], "o-", color=c.SS_COLOUR, ms=3, lw=1.5, label=title)
    span = -x[np.isfinite(x)]
    if identity and span.size:
        ax.plot([span.min(), span.max()], [span.min(), span.max()], "k--", lw=1, label="identity")
    marks = failed & np.isfinite(x)
    if marks.any():
        foot = np.nanmin(-y[ok]) if ok.any() else 0.0
        ax.plot(-x[marks], np.where(np.isfinite(y[marks]), -y[marks], foot), "x", color="C3",
                label="start not walked (outcome in the CSV)")
    ax.set_xlabel(rf"$-\dot\alpha_{{{name}}}(k)$ [rad/s]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    table, study = stability_run(run_dir)
    bounds = ds_bounds(run_dir)
    failed = table["outcome"] != "completed"
    fig, (ax_a, ax_ds, ax_ss) = c.figure(1, 3)
    if bounds is not None:
        bound_curves(ax_a, bounds)
    map_panel(ax_a, table["alphad_iSS"], table["alphad_iDS"], failed, r"$a$: SS + touchdown", "iSS",
              identity=False)
    ax_a.set_ylabel(r"$-\dot\alpha_{iDS}(k)$ [rad/s]")
    ax_a.set_title("SS + touchdown map a and the DS bounds (Fig. 4.5)" if bounds is not None
                   else "SS + touchdown map (the a of Fig. 4.5)", fontsize="medium")
    map_panel(ax_ds, table["alphad_iDS"], table["next_alphad_iDS"], failed, "step map", "iDS")
    ax_ds.set_ylabel(r"$-\dot\alpha_{iDS}(k+1)$ [rad/s]")
    ax_ds.set_title(r"map of $\dot\alpha_{iDS}$ (Fig. 4.6)", fontsize="medium")
    map_panel(ax_ss, table["alphad_iSS"], table["next_alphad_iSS"], failed, "step map", "iSS", study)
    star = study["fixed_point"]
    ax_ss.plot([-star], [-star], "*", color="C3", ms=14,
               label=f"cycle, slope {study['slope']:.2g}" + (" (stable)" if study["stable"] else " (NOT stable)"))
    ax_ss.set_ylabel(r"$-\dot\alpha_{iSS}(k+1)$ [rad/s]")
    ax_ss.set_title(r"map of $\dot\alpha_{iSS}$ (Fig. 4.7)", fontsize="medium")
    ax_ss.legend(fontsize="small")
    fig.suptitle(f"Zero-dynamics Poincaré maps (§4.2.2)\n{run_dir}", fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
