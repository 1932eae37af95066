#!/usr/bin/python3
"""gaitopt plot simulation RUN_DIR [--out FILE]: a closed-loop walk of `gaitopt simulate` — the
output errors of the virtual constraints, the motor torques, the normal forces and friction
cone margins against time, and the phase rate at each step start against the cycle's.

Reads RUN_DIR/summary.json, tracking.csv, steps.csv and trajectory.csv (gaitopt simulate).
"""
import sys

import numpy as np

import _common as c

KIND = "simulation"
JOINTS = ["knee_left", "hip_left", "hip_right", "knee_right"]


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    summary, tracking, steps, traj = c.simulation_run(KIND, run_dir)
    c.require_columns(KIND, f"{run_dir}/tracking.csv", tracking,
                      ["t", "error1", "error2", "error3", "error4", "R1z", "R2z",
                       "cone_margin1", "cone_margin2"])
    c.require_columns(KIND, f"{run_dir}/steps.csv", steps, ["step", "alphad_start"])
    c.require_columns(KIND, f"{run_dir}/trajectory.csv", traj, ["t"] + [f"tau_{j}" for j in JOINTS])
    fig, axes = c.figure(2, 2)
    t = tracking["t"]
    ax = axes[0, 0]
    for k in range(1, 5):
        ax.plot(t, 1e3 * tracking[f"error{k}"], lw=1, label=f"$y_{k}$")
    ax.set(xlabel="time [s]", ylabel="output error [mrad]",
           title="virtual-constraint outputs y = δ − δ_d(α)")
    ax.legend(fontsize="small", ncol=2)
    ax = axes[0, 1]
    for j in JOINTS:
        ax.plot(traj["t"], traj[f"tau_{j}"], lw=1, label=j)
    ax.set(xlabel="time [s]", ylabel="motor torque [N·m]",
           title=f"torques ({summary.get('saturated_samples', 0)} saturated samples)")
    ax.legend(fontsize="small", ncol=2)
    ax = axes[1, 0]
    ax.plot(t, tracking["R1z"], lw=1, label="$R_{1z}$ (leg 1)")
    ax.plot(t, tracking["R2z"], lw=1, label="$R_{2z}$ (leg 2)")
    ax.set(xlabel="time [s]", ylabel="normal force [N]", title="ground reactions and cone margins")
    margins = ax.twinx()
    margins.plot(t, tracking["cone_margin1"], "--", lw=0.8, color="C2", label="cone margin 1")
    margins.plot(t, tracking["cone_margin2"], "--", lw=0.8, color="C3", label="cone margin 2")
    margins.set_ylabel("μ R_z − |R_x| [N]")
    ax.legend(fontsize="small", loc="upper left")
    margins.legend(fontsize="small", loc="upper right")
    ax = axes[1, 1]
    ax.plot(steps["step"], steps["alphad_start"], "o-", ms=4, label="step start")
    cycle = summary.get("cycle_alphad_start")
    if cycle is not None:
        ax.axhline(cycle, color="k", lw=1, ls=":", label="the gait's cycle")
    ax.set(xlabel="step", ylabel="α̇ at the single-support start [rad/s]",
           title="convergence to the cycle")
    ax.legend(fontsize="small")
    for a in axes.flat:
        a.grid(True, alpha=0.3)
    verdict = (f"{summary.get('outcome')}, {summary.get('steps_completed')}/"
               f"{summary.get('steps_requested')} steps, converged "
               f"{'yes' if summary.get('converged_to_cycle') else 'no'}, tracks reference "
               f"{'yes' if summary.get('tracks_reference') else 'no'}")
    fig.suptitle(f"Closed-loop walk: {verdict}\n{run_dir}", fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
