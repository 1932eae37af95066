#!/usr/bin/env bash
# Bad input of examples/mujoco_walk: a missing file and an unknown controller options key must
# each give exit 2 and a message naming the file or the key.
#   examples/mujoco_walk_bad_input.sh GAIT.yaml
# GAITOPT and MUJOCO_WALK name the binaries (default: build/gaitopt, build/examples/mujoco_walk).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
gaitopt="${GAITOPT:-$root/build/gaitopt}"
walk="${MUJOCO_WALK:-$root/build/examples/mujoco_walk}"
gait="${1:?usage: $0 GAIT.yaml}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
robot="$(sed -n 's/^robot: *\([^ #]*\).*/\1/p' "$gait")"
"$gaitopt" export-model --robot "$(dirname "$gait")/$robot" --format mjcf --out "$tmp/robot.xml" \
  >/dev/null || exit 1
"$gaitopt" export --gait "$gait" --steps 2 --format json --out "$tmp/gait.json" >/dev/null || exit 1

failures=0
# expect NAME PATTERN ARGS...: exit 2 and PATTERN (fixed string) in the message.
expect() {
  local name="$1" pattern="$2"
  shift 2
  local out status
  out="$("$walk" "$@" 2>&1)"
  status=$?
  if [ "$status" -ne 2 ] || ! grep -qF -- "$pattern" <<<"$out"; then
    echo "FAIL $name: exit $status (expected 2), message must name '$pattern':"
    echo "$out" | head -5
    failures=$((failures + 1))
  else
    echo "ok   $name: $(head -1 <<<"$out")"
  fi
}

expect missing_export "$tmp/absent.json" --model "$tmp/robot.xml" --export "$tmp/absent.json" \
  --steps 1
expect missing_model "$tmp/absent.xml" --model "$tmp/absent.xml" --export "$tmp/gait.json" --steps 1
expect unknown_option_key "no_such_key" --model "$tmp/robot.xml" --export "$tmp/gait.json" \
  --steps 1 --options "no_such_key: 1"
echo "{" >"$tmp/broken.json"
expect broken_export "$tmp/broken.json" --model "$tmp/robot.xml" --export "$tmp/broken.json" \
  --steps 1
exit $((failures > 0))
