#!/usr/bin/python3
"""Notebook-style example of the Python module: optimise the default step, look at it, and
write it to disk so the CLI can re-use it.

Run after building (cmake ... && cmake --build build):
    PYTHONPATH=build/python /usr/bin/python3 examples/optimize_and_plot.py [OUT_DIR]
OUT_DIR defaults to results/example. The configuration files are found next to this script
(../configs); the `gaitopt` binary is $GAITOPT_BINARY, else build/gaitopt of the repository.
Needs python3-numpy and python3-matplotlib.
"""
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import gaitopt  # noqa: E402

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
binary = os.environ.get("GAITOPT_BINARY") or os.path.join(root, "build", "gaitopt")
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("results", "example")

# 1. Optimise as `gaitopt optimize --config configs/default.yaml --out OUT` (files written too).
result = gaitopt.optimize(os.path.join(root, "configs", "default.yaml"), out=out)
step = result.evaluation
print(f"status {result.status}, C_Gamma {step.C_Gamma:.1f} N^2 m s, "
      f"speed {step.speed:.3f} m/s, {result.iterations} iterations")

# 2. The worst constraints, each in its own unit (g <= 0 when satisfied).
for c in sorted(step.constraints, key=lambda c: -(c["value"] if c["value"] is not None else -1e9))[:3]:
    print(f"  {c['name']:22s} level {c['level']}  {c['value']:+.3g} {c['unit']}")

# 3. The model at the first sample, as `gaitopt model` would print it.
traj = step.trajectory()
robot = gaitopt.Robot(os.path.join(root, "configs", "robot", "rabbit_miossec.yaml"))
print(f"angular momentum about the stance foot at SS start: "
      f"{robot.model(traj.q[0], traj.qd[0])['pinned']['angular_momentum_foot1']:.3f} kg m^2/s")

# 4. A quick figure of the joint torques from the arrays.
fig, ax = plt.subplots(figsize=(8, 4))
for j in range(4):
    ax.plot(traj.t, traj.torques[:, j], label=f"joint {j + 1}")
ax.set_xlabel("time from single-support start [s]")
ax.set_ylabel("motor torque Γ* [N·m]")
ax.set_title("Optimal step at 0.5 m/s: joint torques")
ax.legend()
ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(os.path.join(out, "torques_time.png"), dpi=100)

# 5. The figures of `gaitopt plot` read the files just written.
for kind in ("stick", "torques"):
    subprocess.run([binary, "plot", kind, out], check=True)

# 6. Ten steps at 1 kHz for a controller or a simulator, as `gaitopt export` writes them.
walk = gaitopt.export(os.path.join(out, "gait.yaml"), steps=10, rate=1000.0,
                      out=os.path.join(out, "walk.csv"))
t = walk["samples"]["t"]
print(f"exported {len(t)} samples over {t[-1]:.3f} s to {os.path.join(out, 'walk.csv')}")
print(f"figures and files in {out}")
