#!/usr/bin/python3
"""gaitopt plot phase RUN_DIR [--out FILE]: the step's time law — α(t), the phase portrait
α̇(α) (thesis Fig. 3.14) and the zero-dynamics energy over single support (Fig. 3.15).

Reads RUN_DIR/summary.json and RUN_DIR/trajectory.csv (t, phase, alpha, alphad, sigma,
zd_potential). In single support σ = A[0,:]q̇ is the angular momentum about the stance foot and
σ²/2 + V(α), with V = zd_potential = −Φ(α)/2 of (3.14), is constant (the zero dynamics is
conservative); the energy panel shows both terms and their sum, in (kg·m²)²/s².
"""
import sys

import numpy as np

import _common as c

KIND = "phase"


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    summary, traj = c.step_run(KIND, run_dir)
    c.require_columns(KIND, f"{run_dir}/trajectory.csv", traj, ["t", "phase", "alpha", "alphad", "sigma", "zd_potential"])
    fig, (ax_t, ax_p, ax_e) = c.figure(1, 3)
    for phase, colour, label in (("SS", c.SS_COLOUR, "single support"), ("DS", c.DS_COLOUR, "double support")):
        rows = traj["phase"] == phase
        ax_t.plot(traj["t"][rows], traj["alpha"][rows], color=colour, lw=2, label=label)
        ax_p.plot(traj["alpha"][rows], traj["alphad"][rows], color=colour, lw=2, label=label)
    c.shade_double_support(ax_t, traj)
    ax_t.set_xlabel("time from single-support start [s]")
    ax_t.set_ylabel(r"stance tibia angle $\alpha$ [rad]")
    ax_t.set_title(r"$\alpha(t)$ (decreasing: walking toward +x)", fontsize="medium")
    ax_p.set_xlabel(r"$\alpha$ [rad]")
    ax_p.set_ylabel(r"$\dot\alpha$ [rad/s]")
    ax_p.set_title(r"phase portrait $\dot\alpha(\alpha)$ (3.15)", fontsize="medium")
    ax_p.invert_xaxis()  # time runs left to right

    ss = traj["phase"] == "SS"
    alpha, kinetic, potential = traj["alpha"][ss], 0.5 * traj["sigma"][ss] ** 2, traj["zd_potential"][ss]
    total = kinetic + potential
    ax_e.plot(alpha, kinetic, color="C2", lw=2, label=r"$\sigma^2/2$")
    ax_e.plot(alpha, potential, color="C4", lw=2, label=r"$V(\alpha) = -\Phi(\alpha)/2$")
    ax_e.plot(alpha, total, "k--", lw=1.5, label=f"sum (spread {np.ptp(total):.1e})")
    ax_e.set_xlabel(r"$\alpha$ [rad]")
    ax_e.set_ylabel(r"zero-dynamics energy [(kg$\cdot$m$^2$)$^2$/s$^2$]")
    ax_e.set_title("zero-dynamics energy, single support (3.14)", fontsize="medium")
    ax_e.invert_xaxis()
    for ax in (ax_t, ax_p, ax_e):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    fig.suptitle("Time law: " + c.title(summary, run_dir), fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
