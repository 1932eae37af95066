#!/usr/bin/env bash
# Install what is missing, build, and run the main job on the shipped default config.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh

mkdir -p results
# ---------------------------------------------------------------------------------------------
# MAIN JOB. Only the two lines below change when the main job changes (next:
#   RESULT=results/default
#   build/gaitopt optimize --config configs/default.yaml --out "$RESULT"  ).
RESULT=results/model_default.json
build/gaitopt model --robot configs/robot/rabbit_miossec.yaml --q 0.2,-2.94,-3.24,0.3,-2.74 --qd 0.1,0.2,0.3,0.4,0.5 --qdd 1,0,0,0,0 > "$RESULT"
# ---------------------------------------------------------------------------------------------

echo "run.sh: main job done; result written to $(pwd)/$RESULT"
