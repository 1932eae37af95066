#!/usr/bin/env bash
# Example speed sweep: the default config at 0.2, 0.3, ..., 1.0 m/s on two threads into
# results/sweep_default, then prints results/sweep_default/sweep.csv.
# Override with environment variables: CONFIG, SPEEDS, JOBS, OUT.
# Exit code: that of `gaitopt sweep` (0 all speeds optimal, 3 some not, 2 bad input).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
CONFIG="${CONFIG:-configs/default.yaml}"
SPEEDS="${SPEEDS:-0.2:1.0:0.1}"
JOBS="${JOBS:-2}"
OUT="${OUT:-results/sweep_default}"

# Build first: the full setup (packages + configure) only when there is no build tree yet.
if [ -d build ]; then
  cmake --build build -j"$(nproc)" --target gaitopt
else
  bash scripts/setup.sh
fi

status=0
build/gaitopt sweep --config "$CONFIG" --speeds "$SPEEDS" --jobs "$JOBS" --out "$OUT" || status=$?
if [ -f "$OUT/sweep.csv" ]; then
  echo
  echo "== $OUT/sweep.csv"
  cat "$OUT/sweep.csv"
fi
exit "$status"
