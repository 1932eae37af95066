#!/usr/bin/env bash
# MuJoCo playback acceptance (README, "MuJoCo playback"): for each gait file, exports the robot
# as MJCF and STEPS steps of the gait at 1 kHz into a temporary directory, then plays them with
# examples/mujoco_walk (feedforward + PD, reference indexed by the phase variable). Exit 0 when
# every gait walks all its steps without falling with a mean speed within 5 % of the gait's.
#   scripts/mujoco_walk.sh [-n STEPS] GAIT.yaml...   (default: 20 steps)
# GAITOPT and MUJOCO_WALK name the binaries (default: build/gaitopt, build/examples/mujoco_walk).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
gaitopt="${GAITOPT:-$root/build/gaitopt}"
walk="${MUJOCO_WALK:-$root/build/examples/mujoco_walk}"
steps=20
if [ "${1:-}" = "-n" ]; then steps="$2"; shift 2; fi
[ "$#" -ge 1 ] || { echo "usage: $0 [-n STEPS] GAIT.yaml..." >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
status=0
for gait in "$@"; do
  robot="$(sed -n 's/^robot: *\([^ #]*\).*/\1/p' "$gait")"
  "$gaitopt" export-model --robot "$(dirname "$gait")/$robot" --format mjcf --out "$tmp/robot.xml" >/dev/null
  "$gaitopt" export --gait "$gait" --steps "$steps" --rate 1000 --out "$tmp/walk.csv" >/dev/null
  echo "== $gait"
  "$walk" --model "$tmp/robot.xml" --trajectory "$tmp/walk.csv" || status=$?
done
exit "$status"
