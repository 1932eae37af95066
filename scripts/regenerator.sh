# Shared start of the scripts that write generated blocks of the docs (scripts/docs_blocks.py),
# sourced after `set -euo pipefail`:
#   . "$(dirname "${BASH_SOURCE[0]}")/regenerator.sh"
#   regenerator_start "${1:-}" "PAGE KEY"...
# With --blocks as the first argument it prints the blocks (one `PAGE [KEY]` per line) and ends
# the script; otherwise it moves to the repository root and sets GAITOPT (default
# build/gaitopt) and RESULTS, the folder of the runs' outputs (GAITOPT_RESULTS, default results).

regenerator_start() {  # regenerator_start FIRST_ARGUMENT "PAGE [KEY]"...
  if [ "$1" = --blocks ]; then
    printf '%s\n' "${@:2}"
    exit 0
  fi
  cd "$(dirname "${BASH_SOURCE[0]}")/.."
  GAITOPT="${GAITOPT:-build/gaitopt}"
  RESULTS="${GAITOPT_RESULTS:-results}"
}
