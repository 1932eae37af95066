#!/usr/bin/python3
"""gaitopt plot stick RUN_DIR [--out FILE]: stick-figure sequence of one step (thesis Fig. 3.8)
with the swing-foot path and the clearance curve (Fig. 3.16).

Reads RUN_DIR/summary.json and RUN_DIR/trajectory.csv (joint points x/z_knee1, _hip, _knee2,
_head, x/z_swing, z_clearance); computes nothing but a frame shift: double-support rows, whose
foot 1 is the new front foot, are drawn shifted by the step length d so the whole step shares
the single-support frame (stance foot at the origin).
"""
import sys

import numpy as np

import _common as c

KIND = "stick"
POINTS = ["x_knee1", "z_knee1", "x_hip", "z_hip", "x_knee2", "z_knee2", "x_head", "z_head",
          "x_swing", "z_swing", "z_clearance"]
STANCE, SWING, TRUNK = "C0", "C3", "0.3"


def frames(traj, phase, count):
    rows = np.flatnonzero(traj["phase"] == phase)
    return rows[np.linspace(0, rows.size - 1, count).round().astype(int)]


def draw_posture(ax, traj, i, shift, leg1_colour, leg2_colour, alpha):
    def point(name):
        return np.array([traj["x_" + name][i] + shift, traj["z_" + name][i]])

    foot1 = np.array([shift, 0.0])
    foot2 = np.array([traj["x_swing"][i] + shift, traj["z_swing"][i]])
    hip, head = point("hip"), point("head")
    for chain, colour in (([foot1, point("knee1"), hip], leg1_colour),
                          ([hip, point("knee2"), foot2], leg2_colour), ([hip, head], TRUNK)):
        xy = np.array(chain)
        ax.plot(xy[:, 0], xy[:, 1], "-o", color=colour, alpha=alpha, lw=1.6, ms=2.5)


def main(argv):
    run_dir, out = c.parse_args(KIND, __doc__.splitlines()[0], argv)
    summary, traj = c.step_run(KIND, run_dir)
    c.require_columns(KIND, f"{run_dir}/trajectory.csv", traj, POINTS)
    d = summary["step_length"]
    ss = traj["phase"] == "SS"

    fig, (ax, ax_clear) = c.figure(1, 2, gridspec_kw={"width_ratios": [1.5, 1]})
    ss_frames = frames(traj, "SS", 9)
    for k, i in enumerate(ss_frames):
        draw_posture(ax, traj, i, 0.0, STANCE, SWING, 0.25 + 0.75 * k / (len(ss_frames) - 1))
    # In DS, leg 1 is the former swing leg (now in front): keep each physical leg's colour.
    for i in frames(traj, "DS", 3)[1:]:
        draw_posture(ax, traj, i, d, SWING, STANCE, 0.35)
    ax.plot(traj["x_swing"][ss], traj["z_swing"][ss], color=SWING, lw=2.2, label="swing-foot path (SS)")
    ax.plot(traj["x_swing"][ss], traj["z_clearance"][ss], "k--", lw=1, label="clearance bound (3.49)")
    ax.plot([], [], "-o", color=STANCE, label="stance leg (SS)")
    ax.plot([], [], "-o", color=SWING, label="swing leg (SS)")
    ax.plot([], [], "-", color=TRUNK, label="trunk")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x from the stance foot [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("single support (dark = later), then double support (light, shifted by d)",
                 fontsize="medium")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")  # beside the narrow axes
    ax.grid(True, alpha=0.3)

    ax_clear.plot(traj["x_swing"][ss], 1e3 * traj["z_swing"][ss], color=SWING, lw=2, label="swing foot height")
    ax_clear.plot(traj["x_swing"][ss], 1e3 * traj["z_clearance"][ss], "k--",
                  label=f"clearance bound, z$_{{max}}$ = {1e3 * summary['options']['clearance_height']:.0f} mm")
    ax_clear.set_xlabel("swing-foot x from the stance foot [m]")
    ax_clear.set_ylabel("height above the ground [mm]")
    ax_clear.set_title("swing-foot clearance (3.49)", fontsize="medium")
    ax_clear.legend(fontsize="small")
    ax_clear.grid(True, alpha=0.3)
    fig.suptitle("Step: " + c.title(summary, run_dir), fontsize="medium")
    c.save(KIND, fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
