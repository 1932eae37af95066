# Shared start of the scripts that write generated blocks of the docs (scripts/docs_blocks.py),
# sourced after `set -euo pipefail`:
#   . "$(dirname "${BASH_SOURCE[0]}")/regenerator.sh"
#   regenerator_start "${1:-}" "PAGE KEY"...
# With --blocks as the first argument it prints the blocks (one `PAGE [KEY]` per line) and ends
# the script; otherwise it moves to the repository root and sets GAITOPT (default
# build/gaitopt) and RESULTS, the folder of the runs' outputs (GAITOPT_RESULTS, default results).
# regenerator_optimize (below) runs the optimisations a script quotes.

regenerator_start() {  # regenerator_start FIRST_ARGUMENT "PAGE [KEY]"...
  if [ "$1" = --blocks ]; then
    printf '%s\n' "${@:2}"
    exit 0
  fi
  cd "$(dirname "${BASH_SOURCE[0]}")/.."
  GAITOPT="${GAITOPT:-build/gaitopt}"
  RESULTS="${GAITOPT_RESULTS:-results}"
}

# regenerator_optimize OUT "NAME|CONFIG|FLAGS"...: `$GAITOPT optimize --config CONFIG FLAGS` into
# OUT/NAME (its log OUT/NAME.log), one after the other; exit 0 or 3 (a result that misses a
# constraint is a figure too), anything else ends the script. With REUSE=1 a run whose
# OUT/NAME/summary.json exists is not run again.
regenerator_optimize() {
  local out="$1" entry name config flags rc
  mkdir -p "$out"
  for entry in "${@:2}"; do
    IFS='|' read -r name config flags <<<"$entry"
    if [ "${REUSE:-0}" = 1 ] && [ -f "$out/$name/summary.json" ]; then continue; fi
    rc=0
    # shellcheck disable=SC2086
    "$GAITOPT" optimize --config "$config" $flags --quiet --out "$out/$name" >"$out/$name.log" 2>&1 ||
      rc=$?
    if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then
      echo "$(basename "$0" .sh): optimize $name exits $rc (log: $out/$name.log)" >&2
      exit 1
    fi
  done
}
