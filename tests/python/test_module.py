#!/usr/bin/python3
"""ctest check of the Python module `import gaitopt` against the CLI on the shipped configs.

Usage: test_module.py GAITOPT_BINARY  (with the module's directory on PYTHONPATH)
Values must be EQUAL to the CLI's JSON and CSV (both come from the same documents, printed at
full precision), and bad input must raise gaitopt.ConfigError with the CLI's message.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

import gaitopt

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROBOT = os.path.join(ROOT, "configs", "robot", "rabbit_miossec.yaml")
GAIT = os.path.join(ROOT, "configs", "gait", "default_step.yaml")
CONFIG = os.path.join(ROOT, "configs", "default.yaml")
failures = []


def check(condition, message):
    print(("ok      " if condition else "FAILED  ") + message)
    if not condition:
        failures.append(message)


def cli(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True)


def csv_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [r[k] for r in rows] for k in rows[0]}


def same_trajectory(arrays, path):
    """Every column of the CLI's CSV equals the module's array (NaN for empty fields)."""
    columns = csv_columns(path)
    if set(columns) != set(arrays):
        return False
    for name, text in columns.items():
        if name == "phase":
            if list(arrays[name]) != text:
                return False
            continue
        expected = np.array([float(v) if v else np.nan for v in text])
        if not np.array_equal(expected, arrays[name], equal_nan=True):
            return False
    return True


def test_model(binary):
    q = [-0.2, -2.8, -2.9, 0.3, -2.7]
    qd = [-1.0, 0.4, -0.2, 1.1, -0.6]
    qdd = [0.5, -3.0, 2.0, 1.5, -4.0]
    robot = gaitopt.Robot(ROBOT)
    check(robot.name == "rabbit_miossec", f"Robot.name {robot.name!r}")
    arg = lambda v: ",".join(repr(x) for x in v)  # noqa: E731
    run = cli(binary, "model", "--robot", ROBOT, "--q=" + arg(q), "--qd=" + arg(qd), "--qdd=" + arg(qdd))
    check(run.returncode == 0, f"gaitopt model exit code {run.returncode} {run.stderr}")
    check(robot.model(q, qd, qdd) == json.loads(run.stdout), "Robot.model(q, qd, qdd) == gaitopt model JSON")
    run = cli(binary, "model", "--robot", ROBOT, "--q=" + arg(q), "--rotor", "high_gear")
    check(gaitopt.Robot(ROBOT, rotor="high_gear").model(q) == json.loads(run.stdout),
          "Robot(rotor='high_gear').model(q) == gaitopt model --rotor high_gear JSON")


def test_evaluate(binary, scratch):
    out = os.path.join(scratch, "evaluate")
    run = cli(binary, "evaluate", "--gait", GAIT, "--out", out)
    check(run.returncode == 0, f"gaitopt evaluate exit code {run.returncode}")
    result = gaitopt.evaluate(GAIT)
    trajectory = result.pop("trajectory")
    with open(os.path.join(out, "summary.json")) as f:
        check(result == json.load(f), "evaluate(): summary == summary.json")
    check(result["criteria"]["C_Gamma"] > 0 and len(result["constraints"]) > 10,
          "evaluate(): criteria and constraints present")
    check(isinstance(trajectory["t"], np.ndarray) and trajectory["t"].dtype == float,
          "evaluate(): trajectory columns are float numpy arrays")
    check(same_trajectory(trajectory, os.path.join(out, "trajectory.csv")),
          "evaluate(): trajectory == trajectory.csv, every column")
    check(len(gaitopt.evaluate(GAIT, sample_rate=100.0)["trajectory"]["t"]) < len(trajectory["t"]) / 5,
          "evaluate(sample_rate=100) samples fewer rows")


def test_optimize(binary, scratch):
    cli_out, py_out = os.path.join(scratch, "opt_cli"), os.path.join(scratch, "opt_py")
    run = cli(binary, "optimize", "--config", CONFIG, "--out", cli_out, "--quiet")
    check(run.returncode == 0, f"gaitopt optimize exit code {run.returncode}")
    result = gaitopt.optimize(CONFIG, out=py_out)
    trajectory, gait_yaml = result.pop("trajectory"), result.pop("gait_yaml")
    with open(os.path.join(cli_out, "summary.json")) as f:
        expected = json.load(f)
    for summary in (result, expected):  # the only value that differs between two runs
        summary["solver"].pop("wall_time_s")
    check(result == expected, "optimize(): summary == CLI summary.json (but the wall time)")
    check(result["solver"]["status"] == "optimal", "optimize(): status optimal")
    with open(os.path.join(cli_out, "gait.yaml")) as f:
        check(gait_yaml == f.read(), "optimize(): gait_yaml == CLI gait.yaml")
    check(same_trajectory(trajectory, os.path.join(cli_out, "trajectory.csv")),
          "optimize(): trajectory == CLI trajectory.csv")
    check(os.path.exists(os.path.join(py_out, "gait.yaml")), "optimize(out=...) writes the files")


def test_export(binary, scratch):
    cli_json, py_csv = os.path.join(scratch, "walk_cli.json"), os.path.join(scratch, "walk_py.csv")
    run = cli(binary, "export", "--gait", GAIT, "--steps", "3", "--rate", "250", "--format", "json",
              "--first-stance", "right", "--out", cli_json)
    check(run.returncode == 0, f"gaitopt export exit code {run.returncode}")
    result = gaitopt.export(GAIT, steps=3, rate=250, first_stance="right", out=py_csv)
    with open(cli_json) as f:
        expected = json.load(f)
    samples, expected_samples = result.pop("samples"), expected.pop("samples")
    check(result == expected, "export(): metadata, units and phases == CLI JSON")
    check(sorted(samples) == sorted(expected_samples) and all(
        isinstance(samples[k], np.ndarray) and samples[k].tolist() == expected_samples[k]
        for k in samples), "export(): every samples column == CLI JSON, as numpy arrays")
    check(samples["step"][-1] == 2 and samples["stance"][0] == "right", "export(): 3 steps, right first")
    run = cli(binary, "export", "--gait", GAIT, "--steps", "3", "--rate", "250", "--first-stance", "right",
              "--out", os.path.join(scratch, "walk_cli.csv"))
    with open(py_csv) as f, open(os.path.join(scratch, "walk_cli.csv")) as g:
        check(run.returncode == 0 and f.read() == g.read(), "export(out=...csv) == CLI CSV, byte for byte")
    try:
        gaitopt.export(GAIT, steps=0)
        check(False, "export(steps=0) raised nothing")
    except ValueError as e:
        check("steps >= 1" in str(e), f"export(steps=0): {str(e)!r}")


def test_impact(binary):
    """Robot.impact on the pre-impact state of the shipped impact gait = `gaitopt impact`."""
    gait = os.path.join(ROOT, "configs", "gait", "chevallereau_aoustin_0.75_impact.yaml")
    robot = os.path.join(ROOT, "configs", "robot", "rabbit_chevallereau_aoustin.yaml")
    t = gaitopt.evaluate(gait)["trajectory"]
    i = np.flatnonzero(t["phase"] == "SS")[-1]  # touchdown: the swing foot arrives downward
    q = [t[k][i] for k in ("alpha", "delta1", "delta2", "delta3", "delta4")]
    qd = [t[k][i] for k in ("alphad", "delta1d", "delta2d", "delta3d", "delta4d")]
    r = gaitopt.Robot(robot)
    for model in ("algebraic", "differential"):
        run = cli(binary, "impact", "--robot", robot, "--q=" + ",".join(repr(float(x)) for x in q),
                  "--qd=" + ",".join(repr(float(x)) for x in qd), "--mu", "0.7", "--model", model)
        check(run.returncode == 0, f"gaitopt impact --model {model}: exit code {run.returncode} {run.stderr}")
        result = r.impact(q, qd, 0.7, model=model)
        check(run.returncode == 0 and result == json.loads(run.stdout),
              f"Robot.impact(model={model}) == gaitopt impact JSON")
        check(len(result["solutions"]) >= 1, f"Robot.impact(model={model}): a solution")
    try:
        r.impact(q, [0.0] * 5, 0.7)
        check(False, "impact(qd = 0) raised nothing")
    except ValueError as e:
        check("V2z < 0" in str(e), f"impact(qd = 0): {str(e)!r}")


def test_diagnose(binary, scratch):
    """diagnose() on synthetic data with a known torque offset = `gaitopt diagnose`."""
    data, cli_out, py_out = (os.path.join(scratch, n) for n in ("synth.csv", "diag_cli", "diag_py"))
    run = cli(binary, "synth", "--robot", ROBOT, "--gait", GAIT, "--steps", "12", "--seed", "5",
              "--effect", "torque_offset@knee_left=-3", "--out", data)
    check(run.returncode == 0, f"gaitopt synth exit code {run.returncode} {run.stderr}")
    run = cli(binary, "diagnose", "--robot", ROBOT, "--data", data, "--out", cli_out)
    check(run.returncode == 0, f"gaitopt diagnose exit code {run.returncode} {run.stderr}")
    result = gaitopt.diagnose(ROBOT, data, out=py_out)
    texts = {k: result.pop(k) for k in ("report", "residuals_csv", "extended_robot_yaml")}
    with open(os.path.join(cli_out, "diagnosis.json")) as f:
        check(result == json.load(f), "diagnose(): dict == CLI diagnosis.json")
    for key, name in (("report", "report.md"), ("residuals_csv", "residuals.csv"),
                      ("extended_robot_yaml", "extended_robot.yaml")):
        with open(os.path.join(cli_out, name)) as f, open(os.path.join(py_out, name)) as g:
            text = f.read()
            check(texts[key] == text and g.read() == text, f"diagnose(): {key} == CLI {name}, file too")
    causes = [(c["effect"], c["joint"], c["value"]) for c in result["cause"]]
    check(len(causes) == 1 and causes[0][:2] == ("torque_offset", "knee_left")
          and abs(causes[0][2] + 3.0) < 0.1, f"diagnose(): the offset found {causes}")
    try:
        gaitopt.diagnose(ROBOT, data, holdout=1)
        check(False, "diagnose(holdout=1) raised nothing")
    except ValueError as e:
        check("holdout" in str(e), f"diagnose(holdout=1): {str(e)!r}")


def test_errors(binary, scratch):
    with open(GAIT) as f:
        text = f.read()
    bad = os.path.join(scratch, "bad_step.yaml")
    with open(bad, "w") as f:  # a misspelt option key, relative robot path kept valid
        f.write(text.replace("robot: ", f"robot: {os.path.dirname(GAIT)}/", 1).replace("ss_nodes:", "ss_nodez:"))
    run = cli(binary, "evaluate", "--gait", bad, "--out", os.path.join(scratch, "bad_out"))
    check(run.returncode == 2, f"gaitopt evaluate on a bad file: exit code {run.returncode}")
    prefix = "gaitopt: error: "
    expected = run.stderr.strip()[len(prefix):] if run.stderr.startswith(prefix) else None
    try:
        gaitopt.evaluate(bad)
        check(False, "evaluate(bad file) raised nothing")
    except gaitopt.ConfigError as e:
        check(expected is not None and str(e) == expected, f"ConfigError message {str(e)!r} == CLI's {expected!r}")
        check("ss_nodez" in str(e) and isinstance(e, ValueError), "ConfigError names the key, is a ValueError")
    missing = os.path.join(scratch, "missing.yaml")
    run = cli(binary, "optimize", "--config", missing, "--out", os.path.join(scratch, "x"))
    try:
        gaitopt.optimize(missing)
        check(False, "optimize(missing file) raised nothing")
    except gaitopt.ConfigError as e:
        check(run.returncode == 2 and run.stderr.strip() == prefix + str(e),
              f"optimize(missing): {str(e)!r} == CLI {run.stderr.strip()!r}")


def main(binary):
    with tempfile.TemporaryDirectory(prefix="gaitopt_python_") as scratch:
        test_model(binary)
        test_evaluate(binary, scratch)
        test_optimize(binary, scratch)
        test_export(binary, scratch)
        test_impact(binary)
        test_diagnose(binary, scratch)
        test_errors(binary, scratch)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
