#!/usr/bin/env bash
# The shipped gait files configs/gait/*.yaml, re-optimised, and the other shipped
# configurations measured: runs `gaitopt optimize` on the configuration each gait file comes
# from (one after the other, in the order of their dependencies: a configuration that starts
# from a gait file runs after it), writes the result's gait.yaml to configs/gait/<name>.yaml
# under a header saying how it was made and what it measured, and prints a markdown table of
# status, C_Gamma, iterations and wall time (the figures of docs/formats/optimizer-config.md, "Shipped configurations").
#
#   scripts/regenerate_gaits.sh [name ...]     (default: every entry below)
#
# Outputs of the runs under results/gaits/<name>/, the table in results/gaits/gaits.md.
# Environment: GAITOPT (default build/gaitopt); REUSE=1 writes the gait files and the table from
# the runs already in results/gaits/<name>/ (summary.json, gait.yaml) without running them again.
# The Ipopt runs take minutes (chesse_0.85_ipopt and chesse_0.85_rich more than ten on a loaded
# 2-core machine).
set -uo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
GAITOPT="${GAITOPT:-build/gaitopt}"
OUT=results/gaits
mkdir -p "$OUT"

# name | configuration | speed override (empty: the configuration's) | extra optimize flags |
# description (the header's first line; empty: measured only, no gait file written)
GAITS=(
  "default_step|configs/default.yaml|||The C_Gamma-minimising walking step of the default robot at 0.5 m/s (the default optimum)"
  "optimal_0.3|configs/default.yaml|0.3|--random-starts 8|The C_Gamma-minimising walking step of the default robot at 0.3 m/s"
  "optimal_0.8|configs/default.yaml|0.8||The C_Gamma-minimising walking step of the default robot at 0.8 m/s"
  "default_impact|configs/default_impact.yaml||--random-starts 8|The C_Gamma-minimising step of the default robot at 0.5 m/s landing with an impact at a downward foot speed of at least 0.5 m/s, then single support, with a margin on the single support's energy (alphadot_margin 0.45 rad/s)"
  "chesse_0.85_ipopt|configs/chesse_0.85_ipopt.yaml|||Chesse's model at 0.85 m/s, C_Gamma-minimising with the thesis' 17-parameter step, solved by Ipopt"
  "chesse_0.85|configs/chesse_0.85.yaml|||Chesse's model (rabbit_chesse.yaml) at 0.85 m/s, C_Gamma-minimising with the thesis' 17-parameter step (SLSQP)"
  "chesse_0.85_impact|configs/chesse_0.85_impact.yaml|||Chesse's model at 0.85 m/s, C_Gamma-minimising with an impact landing at a downward foot speed of at least 0.37 m/s, then single support, {ss_points: 3}: the Chesse gait the walking controller walks"
  "chesse_0.85_rich|configs/chesse_0.85_rich.yaml|||Chesse's model at 0.85 m/s with the richer parameterisation {ss_points: 3, ds_points: 1} (27 parameters), from chesse_0.85_ipopt.yaml refined exactly"
  "chevallereau_aoustin_0.75|configs/chevallereau_aoustin_0.75.yaml||--random-starts 8|Chevallereau & Aoustin's robot model at 0.75 m/s, C_Gamma-minimising with the thesis' zero-velocity landing and double support (17 parameters)"
  "chevallereau_aoustin_0.75_impact|configs/chevallereau_aoustin_0.75_impact.yaml||--random-starts 8|Chevallereau & Aoustin's gait family on their robot model at 0.75 m/s: single support only, the swing foot landing with an impact, {ss_points: 3}"
  "chevallereau_aoustin_0.75_impact_rich|configs/chevallereau_aoustin_0.75_impact_rich.yaml|||The same with {ss_points: 11} (59 parameters), from chevallereau_aoustin_0.75_impact.yaml refined exactly"
  "default_ipopt|configs/default_ipopt.yaml|||"
  "chesse_0.85_thesis|configs/chesse_0.85_thesis.yaml|||"
  "chevallereau_aoustin_0.75_thesis|configs/chevallereau_aoustin_0.75_thesis.yaml|||"
  "chesse_0.85_ss3_ds1|configs/chesse_0.85_ss3_ds1.yaml|||"
  "chesse_0.85_ss5_ds2|configs/chesse_0.85_ss5_ds2.yaml|||"
  "chesse_0.85_bspline|configs/chesse_0.85_bspline.yaml|||"
)

# Whether $1 is among the names that follow.
selected() {
  local n
  for n in "${@:2}"; do [ "$n" = "$1" ] && return 0; done
  return 1
}

rows=()
for entry in "${GAITS[@]}"; do
  IFS='|' read -r name config speed flags description <<< "$entry"
  if [ $# -gt 0 ] && ! selected "$name" "$@"; then continue; fi
  run_config="$config"
  made="gaitopt optimize --config $config${flags:+ $flags} --out DIR"
  if [ -n "$speed" ]; then
    # The configuration with another speed, its relative paths resolved against configs/.
    run_config="$OUT/$name.config.yaml"
    sed -e "s#^speed: .*#speed: $speed#" \
        -e "s#^robot: \([^ ]*\)#robot: $ROOT/$(dirname "$config")/\1#" "$config" > "$run_config"
    made="gaitopt optimize --config CONFIG${flags:+ $flags} --out DIR   (CONFIG: $config with speed: $speed)"
  fi
  rc=0
  if [ "${REUSE:-0}" != 1 ] || [ ! -f "$OUT/$name/summary.json" ]; then
    rm -rf "${OUT:?}/$name"
    # shellcheck disable=SC2086
    "$GAITOPT" optimize --config "$run_config" --out "$OUT/$name" --quiet $flags > "$OUT/$name.log" 2>&1
    rc=$?
  fi
  if [ ! -f "$OUT/$name/summary.json" ]; then
    rows+=("| \`$name\` | exit $rc, no summary.json | | | |")
    continue
  fi
  row="$(/usr/bin/python3 - "$OUT/$name" "configs/gait/$name.yaml" "$description" "$made" <<'PY'
import json, os, sys, textwrap
out, target, description, made = sys.argv[1:5]
s = json.load(open(os.path.join(out, "summary.json")))
solver = s["solver"]
status = solver["status"]
row = (f"{status} | {s['criteria']['C_Gamma']:.2f} | {solver['iterations']} "
       f"| {solver['wall_time_s']:.1f} |")
if not description:
    print(f"| `{os.path.basename(made.split()[3])}` | {row}")
    sys.exit(0)
verdict = ("every constraint holds" if s["feasible"] else
           "unmet: " + ", ".join(s["unmet_constraints"]))
text = (f"{description}, found by `{made}` (scripts/regenerate_gaits.sh) and copied from "
        f"DIR/gait.yaml (robot path made relative to this folder): status {status}, "
        f"C_Gamma = {s['criteria']['C_Gamma']:.2f} N^2 m s, {solver['iterations']} iterations, "
        f"{solver['wall_time_s']:.1f} s; {verdict}.")
header = "".join("# " + line + "\n" for line in textwrap.wrap(text, 96))
gait = open(os.path.join(out, "gait.yaml")).read().splitlines(keepends=True)
body = [line for line in gait if not line.startswith("#")]
lines = []
for line in body:
    if line.startswith("robot: "):
        path = line.split()[1]
        line = f"robot: ../robot/{os.path.basename(path)}  # relative to this file\n"
    lines.append(line)
open(target, "w").write(header + "".join(lines))
print(f"| `gait/{os.path.basename(target)}` | {row}")
PY
)"
  rows+=("$row")
done
{
  echo "| file (configs/) | status | C_Gamma [N²·m·s] | iterations | wall time [s] |"
  echo "|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} | tee "$OUT/gaits.md"
