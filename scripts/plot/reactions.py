#!/usr/bin/python3
"""gaitopt plot reactions RUN_DIR [--out FILE]: ground reactions of one step — the normal forces
against their minimum (thesis Fig. 3.11, (3.48)) and the friction-cone use |R_x|/R_z against
the friction coefficient f (Fig. 3.12).

Reads RUN_DIR/summary.json (options friction_coefficient, min_normal_force) and
RUN_DIR/trajectory.csv (t, phase, R1x, R1z, R2x, R2z). Foot 1 is the stance foot in single
support and, after the leg exchange at touchdown, the front foot in double support; foot 2 is
in the air in single support (no reaction drawn there) and the rear foot in double support.
"""
import sys

import numpy as np

import _common as c

KIND = "reactions"


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    summary, traj = c.step_run(KIND, run_dir)
    c.require_columns(KIND, f"{run_dir}/trajectory.csv", traj, ["t", "phase", "R1x", "R1z", "R2x", "R2z"])
    f = summary["options"]["friction_coefficient"]
    r_min = summary["options"]["min_normal_force"]
    t = traj["t"]
    ds = traj["phase"] == "DS"
    feet = [("foot 1 (stance, then front)", traj["R1x"], traj["R1z"], np.ones_like(t, bool), "C0"),
            ("foot 2 (rear, in DS)", traj["R2x"], traj["R2z"], ds, "C3")]

    fig, (ax_n, ax_f) = c.figure(2, 1, sharex=True)
    for label, rx, rz, contact, colour in feet:
        ax_n.plot(t, np.where(contact, rz, np.nan), color=colour, lw=1.8, label=label)
        ratio = np.divide(np.abs(rx), rz, out=np.full_like(rz, np.nan), where=contact & (rz > 0))
        ax_f.plot(t, ratio, color=colour, lw=1.8, label=label)
    ax_n.axhline(r_min, color="k", ls="--", lw=1, label=f"minimum normal force {r_min:g} N")
    ax_f.axhline(f, color="k", ls="--", lw=1, label=f"friction coefficient f = {f:g}")
    c.shade_double_support(ax_n, traj)
    c.shade_double_support(ax_f, traj)
    margin = np.nanmin(np.concatenate([np.where(contact, f * rz - np.abs(rx), np.nan) for _, rx, rz, contact, _ in feet]))
    ax_n.set_ylabel(r"normal force $R_z$ [N]")
    ax_n.set_title("normal ground reactions (3.48)", fontsize="medium")
    ax_f.set_ylabel(r"$|R_x| / R_z$ [–]")
    ax_f.set_title(f"friction-cone use (3.48): smallest margin f·R$_z$ − |R$_x$| = {margin:.1f} N", fontsize="medium")
    ax_f.set_xlabel("time from single-support start [s]")
    ax_f.set_ylim(0.0, 1.15 * f)
    for ax in (ax_n, ax_f):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small", loc="upper left")
    fig.suptitle("Ground reactions: " + c.title(summary, run_dir), fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
