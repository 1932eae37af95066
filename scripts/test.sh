#!/usr/bin/env bash
# Install what is missing, build, and run every test; exits non-zero if any test fails.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh

ctest --test-dir build --output-on-failure -j2
