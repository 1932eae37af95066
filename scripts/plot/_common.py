"""Shared helpers of the gaitopt plot scripts (scripts/plot/<kind>.py).

Each script reads gaitopt's own outputs only: a *step* run directory (summary.json and
trajectory.csv, written by `gaitopt evaluate` or `gaitopt optimize`, or a sweep's per-speed
folder) or a *sweep* directory (sweep.csv, written by `gaitopt sweep` or `sweep-merge`).
Bad input (missing files, a directory of the wrong kind, a bad --out) exits with code 2 and a
message naming the directory or file, as the gaitopt CLI does.
Needs Debian's python3-numpy and python3-matplotlib; run with /usr/bin/python3.
"""
import argparse
import csv
import json
import os
import sys
import tempfile

import numpy as np

EXIT_BAD_INPUT = 2
# Every figure has this size, so a PNG is FIG_SIZE * DPI pixels (checked by the tests).
FIG_SIZE = (12.0, 7.0)
DPI = 100
SS_COLOUR, DS_COLOUR = "C0", "C1"


def out_as_positional(argv):
    """`SCRIPT INPUT --out PNG` (how `gaitopt plot` calls a script) as `SCRIPT INPUT PNG`, for
    the scripts that also take the output as a second positional argument."""
    if "--out" in argv and argv.index("--out") + 1 < len(argv):
        k = argv.index("--out")
        return argv[:k] + argv[k + 2:] + [argv[k + 1]]
    return argv


def fail(kind, message):
    sys.stderr.write(f"gaitopt plot {kind}: error: {message}\n")
    sys.exit(EXIT_BAD_INPUT)


def parse_args(kind, description, argv):
    parser = argparse.ArgumentParser(prog=f"gaitopt plot {kind}", description=description)
    parser.add_argument("run_dir", metavar="RUN_DIR")
    parser.add_argument("--out", metavar="FILE", help=f"FILE.png or FILE.svg (default RUN_DIR/{kind}.png)")
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # argparse exits 2 on bad usage, 0 on --help
        raise SystemExit(EXIT_BAD_INPUT if e.code else 0)
    if not os.path.isdir(args.run_dir):
        fail(kind, f"{args.run_dir}: not a directory")
    out = args.out or os.path.join(args.run_dir, f"{kind}.png")
    if os.path.splitext(out)[1].lower() not in (".png", ".svg"):
        fail(kind, f"--out {out}: the file name must end in .png or .svg")
    return args.run_dir, out


def step_run(kind, run_dir):
    """(summary dict, trajectory columns) of a step run directory, or exit 2 with the reason."""
    summary_path = os.path.join(run_dir, "summary.json")
    trajectory_path = os.path.join(run_dir, "trajectory.csv")
    if os.path.exists(os.path.join(run_dir, "tracking.csv")):
        fail(kind, f"{run_dir}: a gaitopt simulate directory (tracking.csv), not a step run; "
                   "use 'gaitopt plot simulation'")
    if not os.path.exists(summary_path):
        if os.path.exists(os.path.join(run_dir, "sweep.csv")):
            fail(kind, f"{run_dir}: a sweep directory (sweep.csv), not a step run; '{kind}' draws one "
                       "step: give a directory written by gaitopt evaluate or optimize, or one of the "
                       "sweep's speed folders (e.g. v0.500), or use 'gaitopt plot sweep'")
        fail(kind, f"{run_dir}: no summary.json: not a gaitopt step run directory (gaitopt evaluate "
                   "or optimize writes summary.json and trajectory.csv)")
    with open(summary_path) as f:
        try:
            summary = json.load(f)
        except json.JSONDecodeError as e:
            fail(kind, f"{summary_path}: not valid JSON ({e})")
    if not os.path.exists(trajectory_path):
        fail(kind, f"{run_dir}: no trajectory.csv: the step is undefined (summary.json status "
                   f"'{summary.get('status')}', failed level {summary.get('failed_level')}), so there "
                   "is no motion to draw")
    return summary, read_csv(kind, trajectory_path)


def simulation_run(kind, run_dir):
    """(summary, tracking, steps, trajectory) of a gaitopt simulate directory, or exit 2."""
    tracking_path = os.path.join(run_dir, "tracking.csv")
    if not os.path.exists(tracking_path):
        if os.path.exists(os.path.join(run_dir, "sweep.csv")):
            fail(kind, f"{run_dir}: a sweep directory (sweep.csv), not a simulation")
        if os.path.exists(os.path.join(run_dir, "summary.json")):
            fail(kind, f"{run_dir}: a step run directory (summary.json), not a simulation; "
                       f"'{kind}' needs the directory written by gaitopt simulate (tracking.csv)")
        fail(kind, f"{run_dir}: no tracking.csv: not a gaitopt simulate directory")
    with open(os.path.join(run_dir, "summary.json")) as f:
        try:
            summary = json.load(f)
        except json.JSONDecodeError as e:
            fail(kind, f"{run_dir}/summary.json: not valid JSON ({e})")
    return (summary, read_csv(kind, tracking_path),
            read_csv(kind, os.path.join(run_dir, "steps.csv")),
            read_csv(kind, os.path.join(run_dir, "trajectory.csv")))


def sweep_run(kind, run_dir):
    """The sweep.csv rows of a sweep directory, sorted by speed, or exit 2 with the reason."""
    path = os.path.join(run_dir, "sweep.csv")
    if not os.path.exists(path):
        if os.path.exists(os.path.join(run_dir, "summary.json")):
            fail(kind, f"{run_dir}: a step run directory (summary.json), not a sweep; '{kind}' needs "
                       "the directory written by gaitopt sweep or sweep-merge (sweep.csv)")
        fail(kind, f"{run_dir}: no sweep.csv: not a gaitopt sweep directory")
    return read_csv(kind, path, key="speed")


def read_csv(kind, path, key=None):
    """Columns of a gaitopt CSV as a dict name -> numpy array (numbers; empty fields are NaN;
    non-numeric columns such as phase and status stay strings); `#` lines (the metadata of an
    export or a simulated trajectory) are skipped."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows:
        fail(kind, f"{path}: no data rows")
    if key is not None:
        rows.sort(key=lambda r: float(r[key]))
    columns = {}
    for name in rows[0]:
        values = [r[name] for r in rows]
        try:
            columns[name] = np.array([float(v) if v.strip() else np.nan for v in values])
        except ValueError:
            columns[name] = np.array(values)
    return columns


def require_columns(kind, path, columns, names):
    missing = [n for n in names if n not in columns]
    if missing:
        fail(kind, f"{path}: missing columns {', '.join(missing)} (written by an older gaitopt? "
                   "re-run gaitopt evaluate on its gait.yaml)")


def figure(rows, cols, **kwargs):
    # Imported here, after the run directory was checked: a rejected directory fails fast.
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(rows, cols, figsize=FIG_SIZE, **kwargs)


def shade_double_support(ax, traj):
    """Grey band over the double-support times of a time axis."""
    t = traj["t"][traj["phase"] == "DS"]
    if t.size:
        ax.axvspan(t.min(), t.max(), color="0.9", zorder=0, label="double support")


def title(summary, run_dir):
    crit = summary.get("criteria") or {}
    c_gamma = crit.get("C_Gamma")
    parts = [f"{summary.get('robot', '?')}", f"v = {summary['speed']:.3f} m/s" if summary.get("speed") else None,
             f"d = {summary['step_length']:.3f} m" if summary.get("step_length") else None,
             f"$C_\\Gamma$ = {c_gamma:.1f} N$^2\\cdot$m$\\cdot$s" if c_gamma is not None else None]
    return "  ".join(p for p in parts if p) + f"\n{run_dir}"


def write_figure(out, write):
    """Calls write(path) so that `out` is the old or the new figure, never a partial one, and
    returns the name to report. Under `gaitopt plot` (GAITOPT_PLOT_OUT set) `out` is a fresh
    name in gaitopt's private staging folder, which gaitopt publishes; run directly, the figure
    goes to a new random name beside `out` (created exclusively) and is renamed over it."""
    shown = os.environ.get("GAITOPT_PLOT_OUT")
    if shown:
        write(out)
        return shown
    directory = os.path.dirname(out)
    if directory:
        os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=directory or ".", prefix=f".{os.path.basename(out)}.",
                               suffix=os.path.splitext(out)[1])
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, out)
    except BaseException:
        os.unlink(tmp)
        raise
    return out


def save(kind, fig, out):
    fig.tight_layout()
    shown = write_figure(out, lambda path: fig.savefig(path, dpi=DPI))
    print(f"gaitopt plot {kind}: wrote {shown}")
