#!/usr/bin/env bash
# Shared first half of scripts/run.sh and scripts/test.sh: install the Debian packages gaitopt
# needs (only those missing) and build the project in Release mode into build/.
# Run as `bash scripts/setup.sh` by run.sh, as `bash scripts/setup.sh --test` by test.sh (the
# test-only packages too); works from any current directory.
set -euo pipefail

GAITOPT_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

GAITOPT_PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev coinor-libipopt-dev libnlopt-cxx-dev libyaml-cpp-dev libcli11-dev catch2
  libssl-dev libmujoco-dev liburdfdom-dev libsundials-dev
  git python3 python3-numpy python3-matplotlib python3-pil pybind11-dev python3-pybind11 python3-dev
  clang libclang-rt-14-dev  # libFuzzer harnesses (scripts/fuzz.sh, CI smoke run)
)
# Test-only: the one-node Slurm cluster of the slurm_sweep test (tests/slurm/).
GAITOPT_TEST_PACKAGES=(slurm-wlm munge)
case "${1:-}" in
  --test) GAITOPT_PACKAGES+=("${GAITOPT_TEST_PACKAGES[@]}") ;;
  "") ;;
  *) echo "setup: error: unknown argument '$1' (expected --test or nothing)" >&2; exit 2 ;;
esac

gaitopt_install_packages() {
  local missing=() pkg status
  for pkg in "${GAITOPT_PACKAGES[@]}"; do
    # Captured rather than piped into `grep -q`, which under pipefail could fail by SIGPIPE.
    status="$(dpkg -s "$pkg" 2>/dev/null || true)"
    case "$status" in
      *"Status: install ok installed"*) ;;
      *) missing+=("$pkg") ;;
    esac
  done
  if [ "${#missing[@]}" -eq 0 ]; then
    echo "setup: all required packages are installed"
    return 0
  fi
  echo "setup: installing missing packages: ${missing[*]}"
  if ! command -v apt-get >/dev/null 2>&1; then
    echo "setup: error: apt-get not found (Debian/Ubuntu expected); install: ${missing[*]}" >&2
    return 1
  fi
  local as_root=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
      as_root=(sudo)
    else
      echo "setup: error: not root and sudo is not available; install as root: ${missing[*]}" >&2
      return 1
    fi
  fi
  # apt's own output goes to a log, shown only when it fails.
  local log
  log="$(mktemp -t gaitopt-apt.XXXXXX.log)"
  if ! { ${as_root[@]+"${as_root[@]}"} env DEBIAN_FRONTEND=noninteractive apt-get update &&
         ${as_root[@]+"${as_root[@]}"} env DEBIAN_FRONTEND=noninteractive apt-get install -y \
           --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    echo "setup: error: apt-get failed (whole log: $log)" >&2
    return 1
  fi
  rm -f "$log"
  echo "setup: installed ${#missing[@]} packages"
}

# The build's output goes to build/build.log, shown only when it fails (VERBOSE=1: on the
# terminal).
gaitopt_build() {
  local log="$GAITOPT_ROOT/build/build.log"
  mkdir -p "$GAITOPT_ROOT/build"
  echo "setup: building gaitopt (Release, build/; log: build/build.log)"
  if [ -n "${VERBOSE:-}" ]; then
    cmake -S "$GAITOPT_ROOT" -B "$GAITOPT_ROOT/build" -DCMAKE_BUILD_TYPE=Release
    cmake --build "$GAITOPT_ROOT/build" -j"$(nproc)"
    return
  fi
  if ! { cmake -S "$GAITOPT_ROOT" -B "$GAITOPT_ROOT/build" -DCMAKE_BUILD_TYPE=Release &&
         cmake --build "$GAITOPT_ROOT/build" -j"$(nproc)"; } >"$log" 2>&1; then
    tail -n 40 "$log" >&2
    echo "setup: error: the build failed (whole log: build/build.log)" >&2
    return 1
  fi
}

gaitopt_install_packages
gaitopt_build
