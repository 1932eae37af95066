#!/usr/bin/env bash
# Time and peak memory of runs at the bounds of docs/reliability.md: diagnose on the largest
# synth file (--steps 300, just under 10^5 samples), export and simulate near 2e5 rows, impact-map
# on 10^6 grid points (algebraic and differential) and on 10^4 friction samples (intervals.csv).
# Prints one markdown row per run (GNU time: wall seconds, maximum resident set size).
#   scripts/measure_input_limits.sh        # GAITOPT=build/gaitopt by default; ~2 min on 1 core
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
GAITOPT="${GAITOPT:-$ROOT/build/gaitopt}"
ROBOT="$ROOT/configs/robot/rabbit_miossec.yaml"
GAIT="$ROOT/configs/gait/default_step.yaml"
Q=-0.4,-2.8415926535897933,-3.3415926535897933,0.50741499796637735,-2.7987334866164235
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT

measure() {  # NAME ARGS...: "| NAME | wall s | peak MB |"
  local name="$1"
  shift
  /usr/bin/time -f "%e %M" -o "$WORK/time" "$GAITOPT" "$@" >/dev/null
  read -r wall kb <"$WORK/time"
  echo "| $name | $wall | $((kb / 1024)) |"
}

echo "| run | wall [s] | peak [MB] |"
echo "|---|---|---|"
measure "synth --steps 300" synth --robot "$ROBOT" --gait "$GAIT" --steps 300 --out "$WORK/s.csv"
echo "| (its samples) | $(($(wc -l <"$WORK/s.csv") - 1)) | |"
measure "diagnose of it" diagnose --quiet --robot "$ROBOT" --data "$WORK/s.csv" --out "$WORK/d"
measure "export --steps 300 --rate 1000" export --gait "$GAIT" --steps 300 --rate 1000 --out "$WORK/e.csv"
measure "simulate --steps 300 --sample-rate 1000" simulate --gait "$GAIT" --steps 300 --sample-rate 1000 --out "$WORK/sim"
measure "impact-map 1000 x 1000 algebraic" impact-map --robot "$ROBOT" --q="$Q" --mu-range 0:1.5:1000 --theta-range=-180:0:1000 --out "$WORK/m1"
measure "impact-map 1000 x 1000 differential" impact-map --robot "$ROBOT" --q="$Q" --mu-range 0:1.5:1000 --theta-range=-180:0:1000 --model differential --out "$WORK/m2"
measure "impact-map 10000 x 100 algebraic" impact-map --robot "$ROBOT" --q="$Q" --mu-range 0:1.5:10000 --theta-range=-180:0:100 --out "$WORK/m3"
