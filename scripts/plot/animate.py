#!/usr/bin/python3
"""gaitopt plot animate EXPORT.csv --out FILE.gif: animated stick figure of the steps of a
`gaitopt export` CSV, with the planned ground reactions as arrows at the feet.

Reads the export's columns only (t, phase, x/z_hip, trunk_angle, phi_hip_J, phi_knee_J,
foot_*, R_*); the knees are placed where the femur and tibia directions of docs/conventions.md's angle
conventions meet (θ_trunk = trunk_angle + π/2, femur = θ_trunk − φ_hip, tibia = femur − φ_knee
− π), so no link length is needed; the trunk is drawn TRUNK_DRAW_LENGTH long. One frame every
1/FPS s of the export's time (the nearest sample), FPS frames per second in the GIF, written
with matplotlib's PillowWriter (Debian python3-pil).
"""
import argparse
import csv
import os
import sys

import numpy as np

import _common as c

KIND = "animate"
FPS = 25
ANIM_SIZE = (8.0, 4.5)  # inches; at c.DPI the GIF is 800 × 450 pixels (checked by the tests)
TRUNK_DRAW_LENGTH = 0.6  # m, drawing only
NEWTONS_PER_METRE = 1000.0  # reaction arrows: 1 m drawn per 1000 N
COLUMNS = ["t", "phase", "x_hip", "z_hip", "trunk_angle", "foot_left_x", "foot_left_z",
           "foot_right_x", "foot_right_z", "R_left_x", "R_left_z", "R_right_x", "R_right_z"] + \
          [f"phi_{j}_{s}" for j in ("hip", "knee") for s in ("left", "right")]
LEG_COLOURS = {"left": "C0", "right": "C3"}


def parse_args(argv):
    parser = argparse.ArgumentParser(prog=f"gaitopt plot {KIND}", description=__doc__.splitlines()[0])
    parser.add_argument("export", metavar="EXPORT_CSV")
    parser.add_argument("--out", metavar="FILE", help="FILE.gif (default: the export's name with .gif)")
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # argparse exits 2 on bad usage, 0 on --help
        raise SystemExit(c.EXIT_BAD_INPUT if e.code else 0)
    out = args.out or os.path.splitext(args.export)[0] + ".gif"
    if os.path.splitext(out)[1].lower() != ".gif":
        c.fail(KIND, f"--out {out}: the file name must end in .gif")
    return args.export, out


def read_export(path):
    """Columns of an export CSV (`#` metadata lines skipped) as name -> array, or exit 2."""
    if os.path.isdir(path):
        what = "a sweep directory (sweep.csv)" if os.path.exists(os.path.join(path, "sweep.csv")) else \
            "a step run directory (summary.json)" if os.path.exists(os.path.join(path, "summary.json")) else \
            "a directory"
        c.fail(KIND, f"{path}: {what}, not an export file; '{KIND}' draws the CSV written by "
                     "gaitopt export --format csv")
    if not os.path.isfile(path):
        c.fail(KIND, f"{path}: no such file")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows or any(n not in rows[0] for n in COLUMNS):
        c.fail(KIND, f"{path}: not a gaitopt export CSV (needs the columns {', '.join(COLUMNS)})")
    return {n: np.array([r[n] for r in rows]) if n == "phase" else
            np.array([float(r[n]) for r in rows]) for n in COLUMNS}


def unit(angle):
    return np.array([np.cos(angle), np.sin(angle)])


def knee(hip, foot, femur, tibia):
    """Where hip + a u(femur) = foot − b u(tibia): the knee, without the link lengths."""
    m = np.column_stack([unit(femur), unit(tibia)])
    a, _ = np.linalg.lstsq(m, foot - hip, rcond=None)[0]
    return hip + a * unit(femur)


def posture(ex, i):
    hip = np.array([ex["x_hip"][i], ex["z_hip"][i]])
    trunk = ex["trunk_angle"][i] + np.pi / 2
    legs = {}
    for side in ("left", "right"):
        foot = np.array([ex[f"foot_{side}_x"][i], ex[f"foot_{side}_z"][i]])
        femur = trunk - ex[f"phi_hip_{side}"][i]
        tibia = femur - ex[f"phi_knee_{side}"][i] - np.pi
        legs[side] = (foot, knee(hip, foot, femur, tibia))
    return hip, hip + TRUNK_DRAW_LENGTH * unit(trunk), legs


def frame_rows(t):
    times = np.arange(0.0, t[-1] + 1e-9, 1.0 / FPS)
    return np.abs(t[None, :] - times[:, None]).argmin(axis=1)


def main(argv):
    path, out = parse_args(argv)
    ex = read_export(path)
    rows = frame_rows(ex["t"])
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    fig, ax = plt.subplots(figsize=ANIM_SIZE)
    feet_x = np.concatenate([ex["foot_left_x"], ex["foot_right_x"]])
    top = max(ex["z_hip"].max() + TRUNK_DRAW_LENGTH, 1.0) + 0.1

    def draw(k):
        i = rows[k]
        ax.clear()
        hip, head, legs = posture(ex, i)
        ax.axhline(0.0, color="k", lw=0.8)
        ax.plot(*np.array([hip, head]).T, "-o", color="0.3", lw=2.5, ms=3)
        for side, (foot, kn) in legs.items():
            ax.plot(*np.array([hip, kn, foot]).T, "-o", color=LEG_COLOURS[side], lw=2.5, ms=3,
                    label=f"{side} leg")
            r = np.array([ex[f"R_{side}_x"][i], ex[f"R_{side}_z"][i]]) / NEWTONS_PER_METRE
            if np.hypot(*r) > 1e-3:
                ax.annotate("", xy=foot + r, xytext=foot,
                            arrowprops=dict(arrowstyle="->", color=LEG_COLOURS[side], lw=1.5))
        ax.set_xlim(feet_x.min() - 0.5, feet_x.max() + 0.5)
        ax.set_ylim(-0.05, top)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.legend(loc="upper right", fontsize="small")
        ax.set_title(f"t = {ex['t'][i]:.2f} s  {ex['phase'][i]}   reactions: arrows, "
                     f"1 m = {NEWTONS_PER_METRE:.0f} N\n{path}", fontsize="small")

    anim = FuncAnimation(fig, draw, frames=len(rows))
    shown = c.write_figure(out, lambda path: anim.save(path, writer=PillowWriter(fps=FPS), dpi=c.DPI))
    print(f"gaitopt plot {KIND}: wrote {shown} ({len(rows)} frames at {FPS} fps)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
