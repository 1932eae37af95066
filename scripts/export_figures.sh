#!/usr/bin/env bash
# Figures of the controller export (docs/commands/export.md), measured: rows and file sizes of
# a 20-step export at 1 kHz (CSV and JSON), the largest relative error of the recomposition
# tau = B sdd + C sd^2 + G + K + F over its rows, and the RMS difference of the feedforward
# between the exact and the high-gear rotor models per physical joint.
#
#   scripts/export_figures.sh [GAIT.yaml]   (default configs/gait/default_step.yaml)
#
# Outputs under results/export_figures/. Environment: GAITOPT (default build/gaitopt).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
GAITOPT="${GAITOPT:-build/gaitopt}"
GAIT="${1:-configs/gait/default_step.yaml}"
OUT=results/export_figures
mkdir -p "$OUT"
"$GAITOPT" export --gait "$GAIT" --steps 20 --out "$OUT/walk.csv" >/dev/null
"$GAITOPT" export --gait "$GAIT" --steps 20 --format json --out "$OUT/walk.json" >/dev/null
"$GAITOPT" export --gait "$GAIT" --steps 20 --rotor high_gear --out "$OUT/walk_high_gear.csv" \
  >/dev/null
/usr/bin/python3 - "$OUT" <<'PY'
import csv, math, os, sys

out = sys.argv[1]
joints = ["knee_left", "hip_left", "hip_right", "knee_right"]

def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))

exact, high_gear = rows(f"{out}/walk.csv"), rows(f"{out}/walk_high_gear.csv")
events = sum(1 for r in exact if r["event"] != "0")
print(f"rows: {len(exact)} ({len(exact) - events} at 1 kHz + {events} event rows)")
for name in ("walk.csv", "walk.json"):
    print(f"{name}: {os.path.getsize(f'{out}/{name}') / 1e6:.2f} MB")
worst = 0.0
for r in exact:
    for j in joints:
        parts = [float(r[f"tau_B_{j}"]) * float(r["sdd"]),
                 float(r[f"tau_C_{j}"]) * float(r["sd"]) ** 2,
                 float(r[f"tau_gravity_{j}"]), float(r[f"tau_contact_{j}"]),
                 float(r[f"tau_friction_{j}"])]
        scale = max(abs(p) for p in parts)
        worst = max(worst, abs(sum(parts) - float(r[f"tau_{j}"])) / scale)
print(f"recomposition: largest relative error {worst:.1e}")
for j in joints:
    d = [float(a[f"tau_{j}"]) - float(b[f"tau_{j}"]) for a, b in zip(exact, high_gear)]
    print(f"tau_{j}: exact - high_gear RMS {math.sqrt(sum(x * x for x in d) / len(d)):.3f} N*m")
PY
