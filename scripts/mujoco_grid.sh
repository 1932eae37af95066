#!/usr/bin/env bash
# MuJoCo validation grid of the reference walking controller (docs/walking_controller_mujoco.md):
# for each gait, exports the robot as MJCF and the gait as JSON into a temporary folder, then
# walks examples/mujoco_walk (the controller through its C interface) nominally and under ten
# perturbations, 2 cells at a time. Writes OUT/grid.csv and prints the pass rate; the full grid
# (the shipped gaits, every case, 100 steps) also replaces the table of the docs page, and the
# slopes between the grid's (--slopes alone, the shipped gaits, 100 steps) its second table.
#
#   scripts/mujoco_grid.sh [--steps N] [--cases LIST | --slopes LIST] [--jobs J] [--out DIR]
#                          [GAIT.yaml...]
#
#   --steps N      steps per cell (default 100)
#   --cases LIST   comma-separated subset of the cases below (default: all)
#   --slopes LIST  comma-separated ground slopes [rad], run as the cases slope+X, slope-X instead
#   --jobs J       cells run in parallel (default 2)
#   --out DIR      folder of grid.csv and the cells' logs (default build/mujoco_grid)
#   GAIT.yaml...   gaits (default: the shipped ones below; absent files are skipped with a message)
#
# Exit 0 when every cell walked, 3 when one did not, 2 on bad arguments.
# GAITOPT and MUJOCO_WALK name the binaries (default: build/gaitopt, build/examples/mujoco_walk).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
gaitopt="${GAITOPT:-$root/build/gaitopt}"
walk="${MUJOCO_WALK:-$root/build/examples/mujoco_walk}"
doc=docs/walking_controller_mujoco.md  # its generated block (scripts/docs_blocks.py)

shipped_gaits=(
  configs/gait/optimal_0.3.yaml
  configs/gait/default_step.yaml
  configs/gait/optimal_0.8.yaml
  configs/gait/chesse_0.85_impact.yaml
  configs/gait/chevallereau_aoustin_0.75.yaml
  configs/gait/chevallereau_aoustin_0.75_impact.yaml
  configs/gait/default_impact.yaml
)
# case name and mujoco_walk options, in table order
all_cases=(nominal velocity_x0.9 velocity_x1.1 trunk_mass_x0.9 trunk_mass_x1.1 slope+0.035
           slope-0.035 push+0.2 push-0.2 gain_x0.5 gain_x2)
declare -A case_args=(
  [nominal]=""
  [velocity_x0.9]="--velocity-scale 0.9"
  [velocity_x1.1]="--velocity-scale 1.1"
  [trunk_mass_x0.9]="--trunk-mass-scale 0.9"
  [trunk_mass_x1.1]="--trunk-mass-scale 1.1"
  [slope+0.035]="--slope 0.035"
  [slope-0.035]="--slope -0.035"
  [push+0.2]="--push 0.2"
  [push-0.2]="--push -0.2"
  [gain_x0.5]="--gain-scale 0.5"
  [gain_x2]="--gain-scale 2"
)

usage() { sed -n '9,17p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
steps=100
jobs=2
out="$root/build/mujoco_grid"
cases=("${all_cases[@]}")
gaits=()
slopes=()
cases_given=0
full=1
while [ "$#" -gt 0 ]; do
  case "$1" in
    --steps|--cases|--slopes|--jobs|--out)
      [ -n "${2-}" ] || { echo "mujoco_grid: $1 needs a value" >&2; exit 2; } ;;
  esac
  case "$1" in
    --steps) steps="$2"; full=0; shift 2 ;;
    --cases) IFS=, read -r -a cases <<<"$2"; full=0; cases_given=1; shift 2 ;;
    --slopes) IFS=, read -r -a slopes <<<"$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) usage ;;
    --blocks) printf '%s\n' "$doc" "$doc between_slopes"; exit 0 ;;  # its generated blocks
    -*) echo "mujoco_grid: unknown option $1" >&2; usage ;;
    *) gaits+=("$1"); full=0; shift ;;
  esac
done
bad() { echo "mujoco_grid: $*" >&2; exit 2; }
[[ "$steps" =~ ^[1-9][0-9]*$ ]] || bad "--steps: a positive integer, got '$steps'"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || bad "--jobs: a positive integer, got '$jobs'"
# The slopes between the grid's: cases named slope+X, their own table (block between_slopes).
key=""
if [ "${#slopes[@]}" -gt 0 ]; then
  [ "$cases_given" = 0 ] || bad "--slopes: not with --cases"
  cases=()
  for x in "${slopes[@]}"; do
    [[ "$x" =~ ^[+-]?(0|[1-9][0-9]*)?\.?[0-9]+$ ]] || bad "--slopes: a number in rad, got '$x'"
    name="slope$(printf '%+g' "$x")"
    case_args[$name]="--slope $x"
    cases+=("$name")
  done
  key=between_slopes
fi
for c in "${cases[@]}"; do
  [ -n "${case_args[$c]+set}" ] || bad "--cases: unknown case '$c' (known: ${all_cases[*]})"
done
if [ "${#gaits[@]}" -eq 0 ]; then
  for g in "${shipped_gaits[@]}"; do gaits+=("$root/$g"); done
fi
for exe in "$gaitopt" "$walk"; do
  [ -x "$exe" ] || bad "$exe is not built"
done

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out/cells"
rm -f "$out"/cells/*

# Exports of each present gait: TMP/NAME/robot.xml and gait.json; the cells to run.
: >"$tmp/cells.txt"
: >"$tmp/gaits.txt"
: >"$tmp/absent.txt"
for gait in "${gaits[@]}"; do
  name="$(basename "$gait" .yaml)"
  if [ ! -f "$gait" ]; then
    echo "mujoco_grid: $gait is absent: skipped"
    echo "$name" >>"$tmp/absent.txt"
    continue
  fi
  mkdir -p "$tmp/$name"
  echo "$name" >>"$tmp/gaits.txt"
  robot="$(sed -n 's/^robot: *\([^ #]*\).*/\1/p' "$gait")"
  log="$out/cells/$name.export.log"
  status=0
  "$gaitopt" export-model --robot "$(dirname "$gait")/$robot" --format mjcf \
    --out "$tmp/$name/robot.xml" >"$log" 2>&1 || status=$?
  if [ "$status" = 0 ]; then
    "$gaitopt" export --gait "$gait" --format json --out "$tmp/$name/gait.json" >>"$log" 2>&1 ||
      status=$?
  fi
  if [ "$status" != 0 ]; then
    echo "mujoco_grid: $gait: the export failed (exit $status, $log): its cells fail"
    for c in "${cases[@]}"; do
      printf '%s\n%s\n' "walked,steps,mean_speed_last_half,speed_error_percent,max_slip_mm,reason" \
        "0,0,,,,export_failed" >"$out/cells/${name}__$c.csv"
    done
    continue
  fi
  for c in "${cases[@]}"; do echo "$name $c" >>"$tmp/cells.txt"; done
done

# One cell: NAME CASE -> OUT/cells/NAME__CASE.csv (mujoco_walk's summary) and .log.
run_cell() {
  local name="$1" case="$2" cell="$out/cells/$1__$2"
  # shellcheck disable=SC2086  # the case's options are words
  "$walk" --model "$tmp/$name/robot.xml" --export "$tmp/$name/gait.json" --steps "$steps" \
    ${case_args[$case]} --summary-csv "$cell.csv" --steps-csv "$cell.steps.csv" >"$cell.log" 2>&1
  echo "$? $name $case $(grep -v '^Run with --help' "$cell.log" | tail -1)"
}
export -f run_cell
export tmp out steps walk
export case_args_def="$(declare -p case_args)"
# Each xargs worker is a fresh bash: it gets the case table through case_args_def.
xargs -r -P "$jobs" -L 1 bash -c 'eval "$case_args_def"; run_cell "$@"' _ <"$tmp/cells.txt" |
  while read -r status name case line; do
    printf '%-40s %-16s exit %s  %s\n' "$name" "$case" "$status" "$line"
  done

publish=""
[ "$full" = 1 ] && publish="$doc"
DOCS_BLOCKS="$root/scripts/docs_blocks.py" \
  /usr/bin/python3 - "$out" "$tmp" "$steps" "$publish" "$key" "${cases[@]}" <<'EOF'
import csv, datetime, os, subprocess, sys

out, tmp, steps, doc, key, cases = sys.argv[1:6] + [sys.argv[6:]]
def names(file):
    return [g.strip() for g in open(os.path.join(tmp, file)) if g.strip()]
gaits, absent = names("gaits.txt"), names("absent.txt")
fields = ["gait", "case", "walked", "steps", "mean_speed_last_half", "speed_error_percent",
          "max_slip_mm", "reason"]
rows = []
for g in gaits:
    for c in cases:
        path = os.path.join(out, "cells", f"{g}__{c}.csv")
        if os.path.exists(path):
            with open(path) as f:
                r = next(csv.DictReader(f))
        else:  # no summary: the program stopped on bad input or crashed (see the cell's log)
            r = {"walked": "0", "steps": "0", "mean_speed_last_half": "", "speed_error_percent": "",
                 "max_slip_mm": "", "reason": "no_result"}
        rows.append({"gait": g, "case": c, **{k: r[k] for k in fields[2:]}})

partial = os.path.join(out, "grid.csv.tmp")
with open(partial, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
os.replace(partial, os.path.join(out, "grid.csv"))
passed = sum(r["walked"] == "1" for r in rows)
total = len(rows)
rate = 100.0 * passed / total if total else 0.0
print(f"mujoco_grid: {passed}/{total} cells walked ({rate:.0f} %), {steps} steps each -> "
      f"{os.path.join(out, 'grid.csv')}")

if doc:
    def cell(r):
        if r["walked"] == "1":
            return f"{float(r['speed_error_percent']):+.2f} %"
        if r["reason"] == "speed_error":
            return f"✗ {float(r['speed_error_percent']):+.1f} %"
        return f"✗ {r['steps']}: {r['reason']}"
    try:
        mujoco = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "libmujoco-dev"],
                                capture_output=True, text=True).stdout.strip() or "unknown"
    except OSError:
        mujoco = "unknown"
    lines = [
        f"Generated by `scripts/mujoco_grid.sh` on {datetime.date.today().isoformat()} "
        f"(MuJoCo {mujoco}, {steps} steps per cell, controller at 1 kHz): "
        f"**{passed}/{total} cells walked ({rate:.0f} %)**.",
        "",
        "A cell gives the mean speed of the last half against the gait's speed when walked, "
        "else ✗ with the steps walked and the reason (or the speed error).",
        "",
        "| gait | " + " | ".join(f"`{c}`" for c in cases) + " |",
        "|---|" + "---|" * len(cases),
    ]
    for g in gaits:
        lines.append(f"| `{g}` | " + " | ".join(cell(r) for r in rows if r["gait"] == g) + " |")
    failures = []
    for r in rows:
        if r["walked"] == "1":
            continue
        log = os.path.join(out, "cells", f"{r['gait']}__{r['case']}.log")
        state = [l.strip() for l in open(log) if " at t = " in l] if os.path.exists(log) else []
        what = state[0] if state else (f"speed error {float(r['speed_error_percent']):+.2f} %"
                                       if r["reason"] == "speed_error" else r["reason"])
        failures.append(f"- `{r['gait']}` `{r['case']}`, steps walked {r['steps']}/{steps}: {what}")
    if failures:
        lines += ["", "Failed cells (a fall: the reason and the state the controller was given "
                  "then; hip in m, angles in rad, rates per s, contact left, right):",
                  ""] + failures
    slips = [float(r["max_slip_mm"]) for r in rows if r["walked"] == "1"]
    if slips:
        lines += ["", f"Largest stance slip in a walked cell: {max(slips):.2f} mm per step."]
    if absent:
        lines += ["", "Not run (gait file absent): "
                  + ", ".join(f"`{g}.yaml`" for g in absent) + "."]
    block = [doc] + ([key] if key else [])
    subprocess.run([sys.executable, os.environ["DOCS_BLOCKS"], "write", "scripts/mujoco_grid.sh"]
                   + block, input="\n".join(lines) + "\n", text=True, check=True)
    print(f"mujoco_grid: table written to {doc}")
sys.exit(0 if passed == total else 3)
EOF
