#!/usr/bin/env bash
# Configures and builds build-san/: clang, AddressSanitizer + UndefinedBehaviorSanitizer, -O2
# without debug information, libFuzzer coverage instrumentation (docs/reliability.md). Builds
# only what the sanitizer test pass and the fuzz runs need: the CLI (the tests call it),
# gaitopt_tests, mujoco_walk when MuJoCo is found (a ctest entry runs it) and every
# fuzz/fuzz_*.cpp harness; no benchmarks, other examples or Python module.
# Used by scripts/test.sh and scripts/fuzz.sh; prints nothing but errors.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-san"
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$ROOT")}" CCACHE_DIR="${CCACHE_DIR:-$HOME/.ccache}"
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_COMPILER=clang++ \
  -DGAITOPT_FUZZ=ON ${launcher[@]+"${launcher[@]}"} >/dev/null
harnesses=()
for source in "$ROOT"/fuzz/fuzz_*.cpp; do
  harnesses+=("$(basename "$source" .cpp)")
done
# Harnesses first: fuzz.sh can start once they are linked.
targets=("${harnesses[@]}" gaitopt gaitopt_tests)
case "$(cmake --build "$BUILD" --target help)" in  # captured: `| grep -q` could fail by SIGPIPE
  *"... mujoco_walk"*) targets+=(mujoco_walk) ;;
esac
cmake --build "$BUILD" -j"$(nproc)" --target "${targets[@]}" >/dev/null
