#!/usr/bin/env bash
# Install what is missing, build, and run the main job on the shipped default config.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh

mkdir -p results
# ---------------------------------------------------------------------------------------------
# MAIN JOB: the C_Gamma-optimal step of the default robot at 0.5 m/s (configs/default.yaml);
# writes summary.json, gait.yaml and trajectory.csv into results/default.
RESULT=results/default
build/gaitopt optimize --config configs/default.yaml --out "$RESULT"
# ---------------------------------------------------------------------------------------------

echo "run.sh: main job done; result written to $(pwd)/$RESULT"
