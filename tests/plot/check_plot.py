#!/usr/bin/python3
"""ctest check of one `gaitopt plot` kind on the shipped sample outputs (tests/data/).

Usage: check_plot.py GAITOPT_BINARY KIND
Draws KIND from its sample directory into a scratch directory and checks that the PNG exists,
has the size of scripts/plot/_common.py (FIG_SIZE × DPI, read from the PNG header), is not
blank (pixel variance) and, for stick, that an SVG can be written too; then that the same kind on a
directory of the wrong kind exits with code 2 and a message saying which kind it got; for
stick also the command's own errors (unknown kind, bad --out, empty GAITOPT_PLOT_SCRIPTS).
"""
import os
import struct
import subprocess
import sys
import tempfile

import matplotlib.image
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STEP_RUN = os.path.join(ROOT, "tests", "data", "sample_run")
SWEEP_RUN = os.path.join(ROOT, "tests", "data", "sample_sweep")
EXPORT = os.path.join(ROOT, "tests", "data", "sample_export.csv")  # gaitopt export, 2 steps, 50 Hz
STABILITY_RUN = os.path.join(ROOT, "tests", "data", "sample_stability")
EXPECTED_SIZE = (1200, 700)  # FIG_SIZE (12 × 7 in) at 100 dpi


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        raise AssertionError(f"{path}: not a PNG file")
    return struct.unpack(">II", head[16:24])


def run(binary, *args):
    return subprocess.run([binary, "plot", *args], capture_output=True, text=True)


def check(condition, message):
    if not condition:
        sys.stderr.write(f"FAILED: {message}\n")
        sys.exit(1)


def check_command(binary, scratch):
    """Unknown kind, bad --out and the GAITOPT_PLOT_SCRIPTS override: exit 2 with a message."""
    result = run(binary, "nosuch", STEP_RUN)
    check(result.returncode == 2 and "unknown figure 'nosuch'; one of: " in result.stderr
          and all(k in result.stderr for k in ("phase", "reactions", "stick", "sweep", "torques")), f"unknown kind: {result.returncode} {result.stderr!r}")
    result = run(binary, "stick", STEP_RUN, "--out", os.path.join(scratch, "x.pdf"))
    check(result.returncode == 2 and "must end in .png or .svg" in result.stderr, f"--out x.pdf: {result.stderr!r}")
    empty = os.path.join(scratch, "no_scripts")
    os.mkdir(empty)
    result = subprocess.run([binary, "plot", "stick", STEP_RUN], capture_output=True, text=True,
                            env=dict(os.environ, GAITOPT_PLOT_SCRIPTS=empty))
    check(result.returncode == 2 and f"no figure scripts in {empty}" in result.stderr,
          f"GAITOPT_PLOT_SCRIPTS: {result.stderr!r}")


def check_animate(binary):
    """animate on the shipped 2-step export (50 Hz): the GIF's size and frame count (one frame
    per 1/25 s of the export's time), not blank; a run directory and a .png are refused."""
    from PIL import Image

    with open(EXPORT) as f:
        t_end = float([line for line in f if not line.startswith("#")][-1].split(",")[0])
    with tempfile.TemporaryDirectory(prefix="gaitopt_plot_animate_") as scratch:
        gif = os.path.join(scratch, "walk.gif")
        result = run(binary, "animate", EXPORT, "--out", gif)
        check(result.returncode == 0, f"exit code {result.returncode}: {result.stderr}")
        with Image.open(gif) as im:
            frames = im.n_frames
            check(im.format == "GIF" and im.size == (800, 450), f"GIF {im.format} {im.size} != (800, 450)")
            im.seek(frames // 2)
            grey = np.asarray(im.convert("L"), dtype=float) / 255.0
        expected = int(np.floor(t_end * 25 + 1e-9)) + 1
        print(f"animate: {frames} frames (expected {expected}), middle-frame variance {np.var(grey):.4f}")
        check(frames == expected, f"{frames} frames, expected {expected}")
        check(np.var(grey) > 0.005, "blank middle frame")
        rejected = os.path.join(scratch, "rejected.gif")
        result = run(binary, "animate", STEP_RUN, "--out", rejected)
        check(result.returncode == 2 and f"{STEP_RUN}: a step run directory (summary.json), not an export file"
              in result.stderr, f"run directory: {result.returncode} {result.stderr!r}")
        result = run(binary, "animate", EXPORT, "--out", os.path.join(scratch, "walk.png"))
        check(result.returncode == 2 and "must end in .gif" in result.stderr, f".png: {result.stderr!r}")
        check(not os.path.exists(rejected), "a file was written for a rejected input")
    return 0


def main(binary, kind):
    if kind == "animate":
        return check_animate(binary)
    good, wrong, wrong_name = (SWEEP_RUN, STEP_RUN, "a step run directory") if kind == "sweep" \
        else (STABILITY_RUN, STEP_RUN, "a step run directory") if kind == "zero_dynamics" \
        else (STEP_RUN, SWEEP_RUN, "a sweep directory")
    with tempfile.TemporaryDirectory(prefix=f"gaitopt_plot_{kind}_") as scratch:
        png = os.path.join(scratch, f"{kind}.png")
        result = run(binary, kind, good, "--out", png)
        check(result.returncode == 0, f"exit code {result.returncode}: {result.stderr}")
        check(os.path.isfile(png), f"{png} not written")
        check(png_size(png) == EXPECTED_SIZE, f"PNG size {png_size(png)} != {EXPECTED_SIZE}")
        rgb = matplotlib.image.imread(png)[..., :3]
        # Not blank: a white image has pixel variance 0. Data drawn, not only axes: the curves
        # are coloured while frames, grids and text are grey; the same 2×3 axes with labels,
        # titles and grids but no data have 0 coloured pixels (measured), these figures ~1 %.
        variance = float(np.var(rgb.mean(axis=2)))
        coloured = float(np.mean(rgb.max(axis=2) - rgb.min(axis=2) > 0.3))
        print(f"{kind}: {png_size(png)}, pixel variance {variance:.4f}, coloured fraction {coloured:.4f}")
        check(variance > 0.005, f"pixel variance {variance} too small: blank figure")
        check(coloured > 0.003, f"only {coloured:.4f} of the pixels are coloured: no data drawn?")

        if kind == "stick":  # SVG output is the same code path for every kind
            svg = os.path.join(scratch, f"{kind}.svg")
            result = run(binary, kind, good, "--out", svg)
            check(result.returncode == 0 and "<svg" in open(svg).read(1000), f"SVG not written: {result.stderr}")

        if kind == "stick":  # the command's own checks, once
            check_command(binary, scratch)

        rejected = os.path.join(scratch, "rejected.png")
        result = run(binary, kind, wrong, "--out", rejected)
        check(result.returncode == 2, f"wrong kind: exit code {result.returncode}, expected 2")
        expected = f"gaitopt plot {kind}: error: {wrong}: {wrong_name}"
        check(expected in result.stderr, f"wrong kind: message {result.stderr!r} lacks {expected!r}")
        check(not os.path.exists(rejected), "wrong kind: a file was written")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
