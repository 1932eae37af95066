#!/usr/bin/python3
"""ctest check of examples/optimize_and_plot.py (the Python module's example).

Usage: check_example.py GAITOPT_BINARY   (PYTHONPATH must reach the built module)
Runs the example into a scratch directory and checks what it claims to write: the optimiser's
files, whose summary.json agrees with the printed status and criterion; three non-blank
figures; and walk.csv, 10 steps at 1 kHz (one row per millisecond of 10 (T_SS + T_DS), plus
the first, and the rows at the touchdown and lift-off instants), whose stance foot alternates.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

import matplotlib.image
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def check(condition, message):
    if not condition:
        sys.stderr.write(f"FAILED: {message}\n")
        sys.exit(1)


def main(binary):
    with tempfile.TemporaryDirectory(prefix="gaitopt_example_") as scratch:
        out = os.path.join(scratch, "example")
        result = subprocess.run([sys.executable, os.path.join(ROOT, "examples", "optimize_and_plot.py"), out],
                                capture_output=True, text=True, cwd=scratch,
                                env=dict(os.environ, GAITOPT_BINARY=binary))
        check(result.returncode == 0, f"exit code {result.returncode}: {result.stderr}")
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        printed = f"status {summary['solver']['status']}, C_Gamma {summary['criteria']['C_Gamma']:.1f} N^2 m s"
        check(printed in result.stdout, f"{printed!r} not in the output {result.stdout!r}")
        check(summary["solver"]["status"] == "optimal", f"status {summary['solver']['status']}")
        for name in ("gait.yaml", "trajectory.csv"):
            check(os.path.getsize(os.path.join(out, name)) > 0, f"{name} missing or empty")
        for name in ("stick.png", "torques.png", "torques_time.png"):
            grey = matplotlib.image.imread(os.path.join(out, name))[..., :3].mean(axis=2)
            check(np.var(grey) > 0.005, f"{name} blank (pixel variance {np.var(grey)})")
        with open(os.path.join(out, "walk.csv")) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        step = summary["T_SS"] + summary["T_DS"]
        expected = int(np.floor(10 * step * 1000 + 1e-9)) + 1
        fixed_rate = [r for r in rows if r["event"] == "0"]
        print(f"example: C_Gamma {summary['criteria']['C_Gamma']:.2f}, walk.csv {len(fixed_rate)} "
              f"fixed-rate rows (expected {expected}) and {len(rows) - len(fixed_rate)} event "
              f"rows, last t {rows[-1]['t']}")
        check(len(fixed_rate) == expected,
              f"walk.csv has {len(fixed_rate)} fixed-rate rows, expected {expected}")
        # A touchdown and a lift-off row pair at each of the 19 phase boundaries.
        check(len(rows) - len(fixed_rate) == 38, f"{len(rows) - len(fixed_rate)} event rows")
        check(abs(float(rows[-1]["t"]) - (expected - 1) / 1000) < 1e-9, f"last t {rows[-1]['t']}")
        stances = [r["stance"] for r in rows if r["phase"] == "SS"]
        changes = sum(a != b for a, b in zip(stances, stances[1:]))
        check(changes == 9, f"the SS stance foot changes {changes} times in 10 steps, expected 9")
        check(f"exported {len(rows)} samples" in result.stdout, "the exported sample count is not printed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
