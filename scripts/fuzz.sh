#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ (clang, -fsanitize=fuzzer,address,undefined) in
# build-san/, the build directory the sanitizer test pass shares (scripts/build_san.sh), and runs
# each one in turn at nice 10, seeded from the shipped files (docs/reliability.md).
#   scripts/fuzz.sh                 # >= 10^6 executions per harness (default RUNS=1000000)
#   scripts/fuzz.sh --smoke [SEC]   # about SEC seconds per harness (default 20), as in CI
# HARNESSES="fuzz_robot_yaml ..." runs only those (e.g. one per core in parallel).
# Prints one line per harness (executions, seconds, exec/s, coverage, crashes) and exits non-zero
# on a finding; a crashing input is kept as build-san/findings/<harness>/crash-*.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-san"
RUNS="${RUNS:-1000000}"
LIMIT=()
if [ "${1:-}" = "--smoke" ]; then
  LIMIT=(-max_total_time="${2:-20}")
  RUNS=-1
fi

# Seeds of each harness: the shipped files it reads. A new reader adds a line here.
declare -A SEEDS=(
  [fuzz_robot_yaml]="configs/robot/*.yaml fuzz/seeds/aliases.yaml"
  [fuzz_gait_yaml]="configs/gait/*.yaml fuzz/seeds/aliases.yaml"
  [fuzz_config_yaml]="configs/*.yaml fuzz/seeds/aliases.yaml"
  [fuzz_sweep_csv]="fuzz/seeds/sweep.csv"
  [fuzz_measured_csv]="fuzz/seeds/measured*.csv"
  [fuzz_opensim_table]="fuzz/seeds/*.mot fuzz/seeds/*.sto"
  [fuzz_trc_file]="fuzz/seeds/*.trc"
  [fuzz_osim_model]="fuzz/seeds/model.osim"
)

bash "$ROOT/scripts/build_san.sh"
harnesses="${HARNESSES:-$(printf '%s\n' "${!SEEDS[@]}" | sort)}"

status=0
cd "$ROOT"
for harness in $harnesses; do
  corpus="$BUILD/corpus/$harness" findings="$BUILD/findings/$harness"
  rm -rf "$corpus"
  mkdir -p "$corpus" "$findings"
  # shellcheck disable=SC2086  # the patterns are meant to be expanded
  cp ${SEEDS[$harness]} "$corpus/"
  log="$BUILD/$harness.log"
  set +e
  nice -n 10 "$BUILD/fuzz/$harness" -runs="$RUNS" "${LIMIT[@]}" -max_len=16384 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 "$corpus" >"$log" 2>&1
  code=$?
  set -e
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  seconds="$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)"
  coverage="$(sed -n 's/^#[0-9]*[[:space:]]*DONE *cov: \([0-9]*\) ft: \([0-9]*\).*/cov \1, ft \2/p' "$log" | tail -1)"
  crashes="$(find "$findings" -type f | wc -l)"
  echo "$harness: ${runs:-?} executions in ${seconds:-?} s (${rate:-?}/s), ${coverage:-cov ?}," \
    "$crashes crash(es), exit $code"
  if [ "$code" -ne 0 ] || [ "$crashes" -ne 0 ]; then
    status=1
    tail -40 "$log"
  fi
done
exit "$status"
