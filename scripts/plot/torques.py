#!/usr/bin/python3
"""gaitopt plot torques RUN_DIR [--out FILE]: motor torque Γ* of each joint against its joint
speed, inside the torque–speed envelope (thesis Fig. 3.10, constraint (3.46)–(3.47)).

Reads RUN_DIR/summary.json and RUN_DIR/trajectory.csv (gamma1..4, omega1..4, gamma_max1..4:
the envelope Γmax(ω) the constraint used at each sample, so only the visited speeds of the
envelope are drawn).
"""
import sys

import numpy as np

import _common as c

KIND = "torques"
JOINTS = ["knee 1 (stance knee in SS)", "hip 1", "hip 2", "knee 2 (swing knee in SS)"]


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    summary, traj = c.step_run(KIND, run_dir)
    names = [f"{p}{j}" for p in ("gamma", "omega", "gamma_max") for j in range(1, 5)]
    c.require_columns(KIND, f"{run_dir}/trajectory.csv", traj, names)
    fig, axes = c.figure(2, 2)
    for j, (ax, joint) in enumerate(zip(axes.flat, JOINTS), start=1):
        omega, gamma, limit = traj[f"omega{j}"], traj[f"gamma{j}"], traj[f"gamma_max{j}"]
        order = np.argsort(omega)
        ax.fill_between(omega[order], -limit[order], limit[order], color="0.92", label=r"envelope $\pm\Gamma_{max}(\omega)$ (3.47)")
        ax.plot(omega[order], limit[order], "k-", lw=1)
        ax.plot(omega[order], -limit[order], "k-", lw=1)
        for phase, colour, label in (("SS", c.SS_COLOUR, "single support"), ("DS", c.DS_COLOUR, "double support")):
            rows = traj["phase"] == phase
            ax.plot(omega[rows], gamma[rows], ".-", color=colour, ms=2, lw=1.2, label=label)
        worst = np.max(np.abs(gamma) / limit)
        ax.set_title(f"{joint}: peak |Γ*|/Γmax = {worst:.2f}", fontsize="medium")
        ax.set_xlabel(rf"joint speed $\omega_{j}$ [rad/s]")
        ax.set_ylabel(rf"motor torque $\Gamma^*_{j}$ [N$\cdot$m]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize="small")
    fig.suptitle("Joint torques against the torque–speed envelope: " + c.title(summary, run_dir), fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
