#!/usr/bin/env bash
# What CI runs (.ci/run): install what is missing (the test-only packages too), build, check
# that the Slurm cluster test is registered, and run every test; then the same
# suite under AddressSanitizer + UndefinedBehaviorSanitizer in build-san/ (clang, -O2, slow
# optimisation tests in their light form, GAITOPT_TEST_LIGHT=1), and a libFuzzer smoke run of
# every reader from that same build directory (scripts/fuzz.sh --smoke, FUZZ_SECONDS per
# harness, default 20). SANITIZE=0 or FUZZ=0 skip those two passes (docs/reliability.md, for
# their measured time). Prints the time of each part; exits non-zero if any part fails.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
jobs="$(nproc)"
timings=()
part() {  # part NAME COMMAND...: runs and times one part
  local name="$1" start end
  shift
  start="$(date +%s)"
  "$@"
  end="$(date +%s)"
  timings+=("$name: $((end - start)) s")
  echo "test.sh: $name took $((end - start)) s"
}

part "install + Release build" bash scripts/setup.sh --test
# CI has munge and slurm-wlm (setup.sh --test installs them): the cluster test must be there.
listed="$(ctest --test-dir build -N -R '^slurm_sweep$')"
if ! grep -q '^Total Tests: 1$' <<<"$listed"; then
  echo "test.sh: error: the ctest slurm_sweep is not registered in build/ (munged, slurmctld," \
    "slurmd or the Slurm clients not found at configure time)" >&2
  exit 1
fi
part "Release tests" ctest --test-dir build --output-on-failure -j"$jobs"

if [ "${SANITIZE:-1}" = 1 ]; then
  part "sanitizer build" bash scripts/build_san.sh
  # Leaks detected; the first report aborts the test. Per-test times: build-san/junit.xml.
  export GAITOPT_TEST_LIGHT=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  part "sanitizer tests" ctest --test-dir build-san --output-on-failure -j"$jobs" \
    --output-junit junit.xml
  unset GAITOPT_TEST_LIGHT ASAN_OPTIONS UBSAN_OPTIONS
fi

if [ "${FUZZ:-1}" = 1 ]; then
  part "fuzz smoke" bash scripts/fuzz.sh --smoke "${FUZZ_SECONDS:-20}"
fi

printf 'test.sh: %s\n' "${timings[@]}"
