#!/usr/bin/env bash
# Table 3.1 of Miossec 2004 and the richer parameterisations, measured: runs `gaitopt optimize`
# on each configuration given (default: the Table 3.1 set below), one after the other, and
# prints a markdown table of status, criterion, wall time and the constraint groups active at
# the result (max value within 1e-6 of its bound, in the group's unit) from summary.json.
#
#   scripts/table31.sh [config.yaml ...]
#
# Outputs under results/table31/<config name>/ (summary.json, gait.yaml, ...) and
# results/table31/table31.md. Environment: GAITOPT (default build/gaitopt).
# Slow: minutes per configuration on a loaded 2-core machine (the Ipopt ones much longer).
set -uo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
GAITOPT="${GAITOPT:-build/gaitopt}"
OUT=results/table31
mkdir -p "$OUT"
if [ $# -eq 0 ]; then
  set -- configs/chesse_0.85_thesis.yaml configs/chevallereau_aoustin_0.75_thesis.yaml \
         configs/chesse_0.85_ss3_ds1.yaml configs/chesse_0.85_ss5_ds2.yaml \
         configs/chesse_0.85_bspline.yaml
fi
rows=()
for config in "$@"; do
  name="$(basename "$config" .yaml)"
  "$GAITOPT" optimize --config "$config" --out "$OUT/$name" --quiet > "$OUT/$name.log" 2>&1
  rc=$?
  if [ ! -f "$OUT/$name/summary.json" ]; then
    rows+=("| \`$name\` | exit $rc, no summary | | | |")
    continue
  fi
  rows+=("$(/usr/bin/python3 - "$OUT/$name/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
opt = s.get("optimization", s)
solver = opt.get("solver", {})
crit = s["criteria"]
active = sorted({c["name"] for c in s["constraints"]
                 if c.get("value") is not None and c["value"] > -1e-6})
print(f"| `{sys.argv[2]}` | {solver.get('status')} | {crit['C_Gamma']:.1f} | {crit['W']:.2f} "
      f"| {solver.get('wall_time_s', float('nan')):.1f} | {', '.join(active)} |")
PY
)")
done
{
  echo "| config | status | C_Gamma [N²·m·s] | W [J/m] | wall time [s] | active constraint groups |"
  echo "|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} | tee "$OUT/table31.md"
