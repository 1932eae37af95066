#!/usr/bin/python3
"""ctest check of the Python module `import gaitopt` on the shipped configs.

Usage: test_module.py GAITOPT_BINARY  (with the module's directory on PYTHONPATH)
Every value the module returns is checked against a value computed here independently: from the
robot and gait files read with PyYAML, or from physics applied with NumPy to the returned
trajectory (kinematics by finite differences, Newton's and Euler's laws for the whole robot,
the criterion by quadrature, the geometry of the links). The CLI only makes the measured data
of the diagnosis.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import yaml

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


def close(a, b, rtol, atol=0.0):
    return bool(np.all(np.abs(np.asarray(a) - np.asarray(b)) <= atol + rtol * np.abs(np.asarray(b))))


def raises(exception, call):
    try:
        call()
    except exception as e:
        return str(e)
    return None


def load_yaml(path):
    with open(path) as f:
        return yaml.safe_load(f)


def phase_slices(traj):
    """The SS rows, then the DS rows (each phase closed by a row at its exact end)."""
    n_ss = int(np.count_nonzero(traj.phase == "SS"))
    return slice(0, n_ss), slice(n_ss, len(traj.t))


def uniform(p):
    """The rows of a phase at t = k / rate (without its exact end row, closer to the one before)."""
    return slice(p.start, p.stop - 1)


def central(x, t):
    """Central differences of x (rows) over uniformly spaced t at the interior rows."""
    return (x[2:] - x[:-2]) / (t[2:] - t[:-2])[:, None]


def test_robot():
    doc = load_yaml(ROBOT)
    robot = gaitopt.Robot(ROBOT)
    check(robot.name == doc["name"], f"Robot.name {robot.name!r}")
    masses = [doc["masses"][f"m{i}"] for i in range(1, 6)]
    check(robot.masses.tolist() == masses, f"Robot.masses {robot.masses} == the file's {masses}")
    total = sum(masses) + doc["support_bar"]["equivalent_mass"]
    check(abs(robot.total_mass - total) < 1e-12,
          f"Robot.total_mass {robot.total_mass} == segments + support bar {total} kg (1.24)")
    check(robot.lengths == doc["lengths"], f"Robot.lengths {robot.lengths}")
    check(robot.gear_ratio == doc["motors"]["gear_ratio"] and robot.gravity == doc["gravity"],
          "Robot.gear_ratio, gravity as in the file")
    check(robot.coulomb.tolist() == doc["friction"]["coulomb"], "Robot.coulomb as in the file")
    check(raises(ValueError, lambda: gaitopt.Robot(ROBOT, rotor="geared")) is not None,
          "Robot(rotor='geared') raises ValueError")

    # Model terms: A symmetric positive definite; G the gradient of the potential M g z_com.
    q = np.array([-0.2, -2.8, -2.9, 0.3, -2.7])
    qd = np.array([-1.0, 0.4, -0.2, 1.1, -0.6])
    pinned = robot.model(list(q), list(qd))["pinned"]
    A = np.array(pinned["A"])
    check(np.allclose(A, A.T, atol=1e-12) and np.all(np.linalg.eigvalsh(A) > 0), "Robot.model: A symmetric PD")
    h, weight = 1e-6, robot.total_mass * doc["gravity"]
    grad = [weight * (robot.model(list(q + h * e))["pinned"]["com"][1] -
                      robot.model(list(q - h * e))["pinned"]["com"][1]) / (2 * h) for e in np.eye(5)]
    check(close(pinned["G"], grad, 1e-6, 1e-6), f"Robot.model: G {pinned['G']} == d(M g z_com)/dq {grad}")


def test_gait():
    doc = load_yaml(GAIT)
    gait = gaitopt.Gait(GAIT)
    check(gait.parameter_names == list(doc["parameters"]), f"Gait.parameter_names {gait.parameter_names}")
    values = [doc["parameters"][k] for k in gait.parameter_names]
    check(isinstance(gait.parameters, np.ndarray) and gait.parameters.tolist() == values,
          "Gait.parameters: a NumPy array of the file's values")
    check(gait.robot.name == "rabbit_miossec" and os.path.samefile(gait.robot_path, ROBOT),
          f"Gait.robot_path {gait.robot_path}")
    check(gait.sample_rate == doc["options"]["sample_rate"] and gait.target_speed == doc["options"]["target_speed"],
          "Gait.sample_rate, target_speed as in the file")


def check_trajectory(label, evaluation, robot_doc, options, rate):
    """Physics of the sampled step, computed here from the returned arrays."""
    traj = evaluation.trajectory(sample_rate=rate)
    ss, ds = phase_slices(traj)
    d, T_SS, T_DS = evaluation.step_length, evaluation.T_SS, evaluation.T_DS
    check(traj.t[0] == 0.0 and abs(traj.t[ss][-1] - T_SS) < 1e-12 and abs(traj.t[-1] - (T_SS + T_DS)) < 1e-12,
          f"{label}: samples from 0 to T_SS (SS), then to T_SS + T_DS (DS)")
    check(traj.q.shape == (len(traj.t), 5) and traj.torques.shape == (len(traj.t), 4)
          and traj.reactions.shape == (len(traj.t), 4), f"{label}: array shapes")

    # C_Gamma (3.28): the integral of Gamma*^T Gamma* over the step per metre, by the trapezoid
    # rule on each phase (the torques jump at the SS/DS switch). With dry friction the smooth
    # sign's layer is not resolved by the default grids: docs/formats/gait-file.md ("dry_friction",
    # dry_friction) states C_Gamma's accuracy then, 0.63 % on the default optimum.
    power = np.sum(traj.torques ** 2, axis=1)
    integral = sum(np.trapz(power[p], traj.t[p]) for p in (ss, ds))
    rtol = 7e-3 if options.get("dry_friction", True) else 2e-6
    check(close(integral / d, evaluation.C_Gamma, rtol),
          f"{label}: C_Gamma {evaluation.C_Gamma:.3f} == quadrature of the torques {integral / d:.3f}")

    # Kinematics: q' and q'' by central differences (error O(h^2), 1e-6 measured at 20 kHz).
    for name, p in (("SS", uniform(ss)), ("DS", uniform(ds))):
        t = traj.t[p]
        scale = np.max(np.abs(traj.qd[p]))
        check(close(central(traj.q[p], t), traj.qd[p][1:-1], 0, 1e-5 * scale), f"{label} {name}: qd == dq/dt")
        scale = np.max(np.abs(traj.qdd[p]))
        check(close(central(traj.qd[p], t), traj.qdd[p][1:-1], 0, 1e-5 * scale), f"{label} {name}: qdd == dqd/dt")

    # Whole robot: M a_com = R1 + R2 + M g, and the angular momentum about foot 1 changes by the
    # moment of gravity and of R2 at foot 2 (the motor torques are internal).
    mass = sum(robot_doc["masses"].values()) + robot_doc["support_bar"]["equivalent_mass"]
    g = robot_doc["gravity"]
    R1, R2 = traj.reactions[:, :2], traj.reactions[:, 2:]
    check(np.max(np.abs(R2[ss])) == 0.0, f"{label}: R2 = 0 in single support")
    for name, p in (("SS", uniform(ss)), ("DS", uniform(ds))):
        t, com = traj.t[p], traj.com[p]
        a_com = (com[2:] - 2 * com[1:-1] + com[:-2]) / ((t[2:] - t[:-2]) / 2)[:, None] ** 2
        force = (R1[p] + R2[p])[1:-1] + np.array([0.0, -mass * g])
        check(close(mass * a_com, force, 0, 1e-5 * mass * g), f"{label} {name}: M a_com == R1 + R2 + M g")
        moment = -mass * g * com[:, 0] + traj.foot2[p][:, 0] * R2[p][:, 1]
        dsigma = central(traj.sigma[p][:, None], t)[:, 0]
        check(close(dsigma, moment[1:-1], 0, 1e-4 * np.max(np.abs(moment))),
              f"{label} {name}: d(sigma)/dt == moment of gravity and R2 about foot 1")

    # Geometry from the robot file: link lengths and reach within the leg lengths.
    L = robot_doc["lengths"]
    lengths = [(traj.knee1, L["l1"]), (traj.hip - traj.knee1, L["l2"]),
               (traj.knee2 - traj.hip, L["l4"]), (traj.foot2 - traj.knee2, L["l5"])]
    check(all(close(np.linalg.norm(v, axis=1), l, 1e-12) for v, l in lengths), f"{label}: links at the file's lengths")
    check(np.all(np.linalg.norm(traj.hip, axis=1) <= L["l1"] + L["l2"] + 1e-12)
          and np.all(np.linalg.norm(traj.hip - traj.foot2, axis=1) <= L["l4"] + L["l5"] + 1e-12),
          f"{label}: hip within reach of both feet")
    # The feet on the ground where they should be: foot 2 at -d then +d in SS, at -d in DS.
    check(close(traj.foot2[0], [-d, 0.0], 0, 1e-9) and close(traj.foot2[ss][-1], [d, 0.0], 0, 1e-9)
          and close(traj.foot2[ds], [-d, 0.0], 0, 1e-9), f"{label}: foot 2 on the ground at -d, +d")

    # The landing foot becomes foot 1: the configuration at DS start is the SS end's with the
    # legs' roles swapped, seen from the new stance foot d ahead.
    i, j, shift = ss.stop - 1, ds.start, np.array([d, 0.0])
    check(close(traj.hip[j], traj.hip[i] - shift, 0, 1e-9) and close(traj.knee1[j], traj.knee2[i] - shift, 0, 1e-9)
          and close(traj.knee2[j], traj.knee1[i] - shift, 0, 1e-9)
          and close(traj.head[j], traj.head[i] - shift, 0, 1e-9), f"{label}: SS end == DS start, legs swapped")
    # A cyclic step: it ends where and how it started.
    check(close(traj.q[-1], traj.q[0], 0, 1e-9) and close(traj.qd[-1], traj.qd[0], 0, 1e-6),
          f"{label}: q, qd at the step's end == at its start")

    # Actuator and contact limits (file values): the envelope's plateau, the friction cone.
    check(np.max(np.abs(traj.torques)) <= max(robot_doc["motors"]["envelope"]["torque"]) + 2e-4,
          f"{label}: |Gamma*| <= the envelope's plateau")
    mu = options.get("friction_coefficient", 0.8)
    check(np.all(np.abs(R1[:, 0]) <= mu * R1[:, 1] + 1e-3), f"{label}: R1 in the friction cone (mu {mu})")
    return traj


def test_evaluate():
    gait_doc, robot_doc = load_yaml(GAIT), load_yaml(ROBOT)
    gait = gaitopt.Gait(GAIT)
    evaluator = gaitopt.GaitEvaluator(gait)
    check(evaluator.parameter_names == gait.parameter_names and evaluator.num_parameters == 17,
          "GaitEvaluator: the thesis' 17 parameters")
    e = evaluator.evaluate()
    p = gait_doc["parameters"]
    check(e.step_length == p["d"] and e.T_DS == p["T_DS"], "evaluate(): step_length, T_DS == d, T_DS of the file")
    check(abs(e.speed - e.step_length / (e.T_SS + e.T_DS)) < 1e-12,
          f"evaluate(): speed {e.speed} == d / (T_SS + T_DS)")
    check(abs(e.speed - gait_doc["options"]["target_speed"]) < 1e-6, "evaluate(): the file's target speed")
    check(e.defined and e.C_Gamma > 0 and e.C_E > 0 and e.W > 0, "evaluate(): defined, positive criteria")
    # The file's comment: every constraint holds, between the nodes too.
    check(e.feasible and e.failed_level is None and e.unmet_constraints == [],
          f"evaluate(): feasible {e.unmet_constraints}, level {e.failed_level}")
    groups = e.constraints
    check(sum(c["count"] for c in groups) == len(e.g)
          and [c["offset"] for c in groups] == list(np.cumsum([0] + [c["count"] for c in groups])[:-1]),
          "evaluate(): the groups tile g")
    check(all(np.all(e.g_levels[c["offset"]:c["offset"] + c["count"]] == c["level"]) for c in groups)
          and set(e.g_levels) == set(range(6)), "evaluate(): g_levels == the groups' levels 0..5")
    check(np.max(e.g) < 1e-4 and all(c["value"] == np.max(c["values"]) for c in groups),
          f"evaluate(): every node entry met (max g {np.max(e.g):.2e}), value = the group's worst")
    traj = check_trajectory("evaluate()", e, robot_doc, gait_doc["options"], 20000.0)
    clear = traj.clearance[traj.phase == "SS"]
    check(np.min(traj.foot2[traj.phase == "SS"][:, 1] - clear) < 0, "evaluate(): the swing foot dips below the bound")
    coarse = e.trajectory(sample_rate=100.0)
    check(len(coarse.t) == (int(e.T_SS * 100) + 2) + (int(e.T_DS * 100) + 2),
          f"trajectory(100): {len(coarse.t)} rows, each phase's every 10 ms from its start and its end")

    # Parameters out of reach: d beyond both legs stretched fails level 0; nothing sampled.
    far = gait.parameters.copy()
    far[gait.parameter_names.index("d")] = 2.0 * sum(robot_doc["lengths"].values())
    bad = evaluator.evaluate(far)
    reach = [c for c in bad.constraints if c["name"] in ("reach_max_iDS", "reach_max_fDS")]
    check(not bad.defined and bad.failed_level == 0 and bad.C_Gamma is None and bad.trajectory() is None,
          f"evaluate(d = 2 legs): undefined at level {bad.failed_level}, no criteria, no trajectory")
    check(len(reach) == 2 and all(c["value"] is not None and c["value"] > 0 for c in reach),
          f"evaluate(d = 2 legs): the DS ends out of reach {[c['value'] for c in reach]}")
    check(raises(ValueError, lambda: evaluator.evaluate(far[:5])) is not None, "evaluate(5 values) raises ValueError")


def test_optimize(binary, scratch):
    config = load_yaml(CONFIG)
    out = os.path.join(scratch, "opt")
    result = gaitopt.optimize(CONFIG, out=out)
    check([n for n in os.listdir(scratch) if ".gaitopt-" in n] == [],
          "optimize(out=...): published, no staging folder left beside it")
    e = result.evaluation
    check(result.status == "optimal" and e.feasible and result.unmet_level is None,
          f"optimize(): {result.status}, feasible {e.feasible}")
    check(abs(e.speed - config["speed"]) < 1e-6 and abs(e.speed - e.step_length / (e.T_SS + e.T_DS)) < 1e-12,
          f"optimize(): speed {e.speed} == the requested {config['speed']} == d / (T_SS + T_DS)")
    check(result.iterations > 0 and len(result.stages) >= 1 and result.parameters.tolist() == e.parameters.tolist(),
          f"optimize(): {result.iterations} iterations, stages {[s['name'] for s in result.stages]}")
    for name in ("summary.json", "gait.yaml", "trajectory.csv"):
        check(os.path.getsize(os.path.join(out, name)) > 0, f"optimize(out=...) writes {name}")
    with open(os.path.join(out, "gait.yaml")) as f:
        check(f.read() == result.gait_yaml, "optimize(): gait_yaml == the file written")
    # The written gait file reads back to the same step.
    again = gaitopt.GaitEvaluator(gaitopt.Gait(os.path.join(out, "gait.yaml"))).evaluate()
    check(again.parameters.tolist() == result.parameters.tolist() and again.C_Gamma == e.C_Gamma,
          "optimize(): gait.yaml evaluates to the same parameters and C_Gamma")
    traj = check_trajectory("optimize()", e, load_yaml(ROBOT), config.get("options") or {}, 20000.0)
    ss = traj.phase == "SS"
    # Feasible: above the bound up to the feasibility tolerance (1e-6 x the group's scale).
    check(np.all(traj.foot2[ss][:, 1] >= traj.clearance[ss] - 1e-8), "optimize(): the swing foot clears the bound")


def test_export(scratch):
    e = gaitopt.evaluate(GAIT)
    path = os.path.join(scratch, "walk.csv")
    walk = gaitopt.export(GAIT, steps=3, rate=250, first_stance="right", out=path)
    t = walk["samples"]["t"][walk["samples"]["event"] == 0]
    check(isinstance(t, np.ndarray) and len(t) == int(np.floor(3 * (e.T_SS + e.T_DS) * 250 + 1e-9)) + 1,
          f"export(): {len(t)} fixed-rate samples over 3 steps of T_SS + T_DS at 250 Hz")
    check(close(np.diff(t), 1 / 250, 1e-9), "export(): fixed-rate samples every 4 ms")
    check(walk["schema_version"] == 2 and walk["feedforward"]["rotor_model"] == "exact",
          "export(): schema 2, exact rotor model")
    stances = walk["samples"]["stance"][walk["samples"]["phase"] == "SS"]
    check(stances[0] == "right" and np.count_nonzero(stances[1:] != stances[:-1]) == 2,
          "export(): right stance first, alternating over 3 steps")
    check(os.path.getsize(path) > 0, "export(out=...) writes the file")
    check("steps >= 1" in (raises(ValueError, lambda: gaitopt.export(GAIT, steps=0)) or ""),
          "export(steps=0) raises ValueError")


def test_impact():
    """Robot.impact at the touchdown of the shipped impact gait: the impulses' physics."""
    gait = os.path.join(ROOT, "configs", "gait", "chevallereau_aoustin_0.75_impact.yaml")
    traj = gaitopt.evaluate(gait).trajectory()
    i = np.flatnonzero(traj.phase == "SS")[-1]  # touchdown: the swing foot arrives downward
    robot = gaitopt.Gait(gait).robot
    for model in ("algebraic", "differential"):
        result = robot.impact(list(traj.q[i]), list(traj.qd[i]), 0.7, model=model)
        solutions = result["solutions"]
        check(len(solutions) >= 1, f"Robot.impact(model={model}): {len(solutions)} solution(s)")
        for s in solutions:
            impulse = np.array(s["impulse_foot2"])
            check(impulse[1] > 0 and abs(impulse[0]) <= 0.7 * impulse[1] + 1e-9 and s["energy_loss"] >= -1e-9,
                  f"Robot.impact(model={model}): impulse {impulse} pushes up inside the cone, energy lost")
    check("V2z < 0" in (raises(ValueError, lambda: robot.impact(list(traj.q[i]), [0.0] * 5, 0.7)) or ""),
          "Robot.impact(qd = 0) raises ValueError")


def test_diagnose(binary, scratch):
    """diagnose() on synthetic data with a known torque offset finds it."""
    data = os.path.join(scratch, "synth.csv")
    run = subprocess.run([binary, "synth", "--robot", ROBOT, "--gait", GAIT, "--steps", "12", "--seed", "5",
                          "--effect", "torque_offset@knee_left=-3", "--out", data], capture_output=True, text=True)
    check(run.returncode == 0, f"gaitopt synth exit code {run.returncode} {run.stderr}")
    result = gaitopt.diagnose(ROBOT, data, holdout=3)
    causes = [(c["effect"], c["joint"], c["value"]) for c in result["causes"]]
    check(len(causes) == 1 and causes[0][:2] == ("torque_offset", "knee_left") and abs(causes[0][2] + 3.0) < 0.1,
          f"diagnose(): the -3 N m knee_left offset found {causes}")
    with open(data) as f:
        lines = f.read().splitlines()
    truth = json.loads("\n".join(line[2:] for line in lines if line.startswith("#")))
    check(truth["effects"] == [{"effect": "torque_offset", "joint": "knee_left", "value": -3, "unit": "N·m"}]
          and not os.path.exists(data + ".truth.json"), f"synth: the truth heads the CSV as '#' lines {truth}")
    header = next(line for line in lines if not line.startswith("#"))
    column = header.split(",").index("step")
    steps = np.loadtxt(data, delimiter=",", comments="#", skiprows=lines.index(header) + 1, usecols=column, dtype=int)
    held = result["holdout_rows"]
    check(len(held) == len(steps) and not np.any(held & result["fit_rows"]),
          "diagnose(): held-out and fit rows, one per sample, disjoint")
    check(len(set(steps[held])) == 12 // 3, f"diagnose(): every 3rd of 12 steps held out ({len(set(steps[held]))})")
    check(result["rms_reduction_pct"]["gamma_knee_left"] > 50.0,
          f"diagnose(): the knee_left torque residual shrinks {result['rms_reduction_pct']['gamma_knee_left']:.1f} %")
    check(result["nominal_residuals"].shape == (len(steps), len(result["channels"])),
          "diagnose(): residuals, samples x channels")
    check(result["extended_robot"].masses.tolist() == gaitopt.Robot(ROBOT).masses.tolist(),
          "diagnose(): the extended robot keeps the masses")
    check("holdout" in (raises(ValueError, lambda: gaitopt.diagnose(ROBOT, data, holdout=1)) or ""),
          "diagnose(holdout=1) raises ValueError")
    test_diagnose_out(data, scratch, result)


def folder(path):
    """Every entry under path (hidden ones included) with its content."""
    entries = {}
    for parent, dirs, files in os.walk(path):
        for name in dirs + files:
            full = os.path.join(parent, name)
            entries[os.path.relpath(full, path)] = "/" if os.path.isdir(full) else open(full, "rb").read()
    return entries


def test_diagnose_out(data, scratch, result):
    """diagnose(out=...) publishes its four files together, as the CLI: a failed run leaves the
    old result and no staging folder; unusable folders raise OutputError with nothing written."""
    box = os.path.join(scratch, "diagnose_box")
    os.mkdir(box)
    out = os.path.join(box, "diagnosis")
    gaitopt.diagnose(ROBOT, data, holdout=3, out=out)
    names = sorted(os.listdir(out))
    check(names == ["diagnosis.json", "extended_robot.yaml", "report.md", "residuals.csv"],
          f"diagnose(out=): the four files {names}")
    with open(os.path.join(out, "report.md"), encoding="utf-8") as f:
        check(f.read() == result["report"], "diagnose(out=): report.md is the returned report")
    before = folder(box)
    check(raises(ValueError, lambda: gaitopt.diagnose(ROBOT, data, holdout=1, out=out)) is not None
          and folder(box) == before, "diagnose(out=) failing mid-way: the old result kept, no staging folder left")
    check(issubclass(gaitopt.OutputError, ValueError), "OutputError is a ValueError")
    with open(os.path.join(box, "notes.txt"), "w") as f:
        f.write("mine\n")
    before = folder(box)
    for bad, message in ((box, "which gaitopt did not write"),
                         ("/", "is the current directory or contains it"),
                         (os.path.join(box, "notes.txt"), "exists and is not a directory")):
        error = raises(gaitopt.OutputError, lambda: gaitopt.diagnose(ROBOT, data, out=bad))
        check(error is not None and message in error and folder(box) == before,
              f"diagnose(out={bad!r}): OutputError, nothing written: {error!r}")


def test_errors(scratch):
    with open(GAIT) as f:
        text = f.read()
    bad = os.path.join(scratch, "bad_step.yaml")
    with open(bad, "w") as f:  # a misspelt option key, relative robot path kept valid
        f.write(text.replace("robot: ", f"robot: {os.path.dirname(GAIT)}/", 1).replace("ss_nodes:", "ss_nodez:"))
    line = 1 + text.split("ss_nodes:")[0].count("\n")
    message = raises(gaitopt.ConfigError, lambda: gaitopt.Gait(bad))
    check(message is not None and "ss_nodez" in message and f":{line}" in message and bad in message,
          f"Gait(bad file): ConfigError naming the file, line {line} and key: {message!r}")
    check(issubclass(gaitopt.ConfigError, ValueError), "ConfigError is a ValueError")
    missing = os.path.join(scratch, "missing.yaml")
    message = raises(gaitopt.ConfigError, lambda: gaitopt.optimize(missing))
    check(message is not None and missing in message, f"optimize(missing file): {message!r}")


def test_viscous_quadrature(scratch):
    """Without dry friction the criteria's integrands are resolved by the default grids: C_Gamma
    equals the torques' quadrature to 2e-6 (the 7e-3 of check_trajectory is dry friction's)."""
    text = open(GAIT, encoding="utf-8").read().replace("dry_friction: true", "dry_friction: false")
    lines = [f"robot: {ROBOT}" if line.startswith("robot:") else line for line in text.splitlines()]
    path = os.path.join(scratch, "viscous_step.yaml")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    e = gaitopt.GaitEvaluator(gaitopt.Gait(path)).evaluate()
    check(e.defined, "viscous step: defined")
    check_trajectory("evaluate(dry_friction: false)", e, load_yaml(ROBOT), {"dry_friction": False}, 20000.0)


def main(binary):
    with tempfile.TemporaryDirectory(prefix="gaitopt_python_") as scratch:
        test_robot()
        test_gait()
        test_evaluate()
        test_viscous_quadrature(scratch)
        test_optimize(binary, scratch)
        test_export(scratch)
        test_impact()
        test_diagnose(binary, scratch)
        test_errors(scratch)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
