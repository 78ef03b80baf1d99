#!/usr/bin/env bash
# Method study (docs/performance.md "Naive setups"): for each model, every
# integrator over a ladder of tolerances, features against a tight-tolerance reference
# (CVODES BDF, rtol = atol = 1e-10, one system), and the cheapest setting whose features all
# meet the accuracy (every feature in ms within 0.01 ms, every one in deg within 0.01 deg).
#
#   bash bench/method_study.sh [CASES...]
#
# A case is CONFIG[:MOTONEURON] (configs/CONFIG.toml; MOTONEURON "spiking" or "rate" sets
# [model] motoneuron). Default: single_joint_fti:spiking single_joint_fti:rate
# three_legs_tetrapod:rate. Environment: PHASMID (default build/phasmid), METHODS (default
# "cvodes_bdf dopri5"), TOLS (default "1e-4 1e-5 1e-6 1e-7 1e-8"), REPEATS (default 1,
# the minimum is kept), PARTITIONING (unset: the kind's choice; "whole", "joints", "neurons":
# [simulation.expert] partitioning), REF_TOL (1e-10), EXPERT_EXTRA (more [simulation.expert]
# lines for the methods' runs, not the reference: "threads = 2").
# Time: CPU seconds (user + system) of `phasmid simulate` minus those of the same run for 1 ms
# of model time (start-up, config, model assembly), so other load on the machine counts less.
# Dimensionless features (fractions, ratios, lags) are reported ("max |d| 1"), not gated.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PHASMID=${PHASMID:-$ROOT/build/phasmid}
METHODS=${METHODS:-"cvodes_bdf dopri5"}
TOLS=${TOLS:-"1e-4 1e-5 1e-6 1e-7 1e-8"}
REPEATS=${REPEATS:-1}
REF_TOL=${REF_TOL:-1e-10}
CASES=("$@")
[ ${#CASES[@]} -gt 0 ] || CASES=(single_joint_fti:spiking single_joint_fti:rate three_legs_tetrapod:rate)
[ -x "$PHASMID" ] || { echo "method_study: $PHASMID not found (cmake --build build --target phasmid)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# variant CONFIG MN METHOD TOL [T_END] > toml: the config with its [simulation] tolerances,
# integrator (and partitioning, motoneurons, horizon) replaced.
variant() {
  local cfg=$ROOT/configs/$1.toml mn=$2 method=$3 tol=$4 tend=${5:-}
  local sim="[simulation]\nrtol = $tol\natol = $tol\nintegrator = \"$method\"" expert=""
  [ -n "${PARTITIONING:-}" ] && expert="partitioning = \"$PARTITIONING\""
  [ -n "${EXPERT_EXTRA:-}" ] && expert="${expert:+$expert\n}$EXPERT_EXTRA"
  if [ "$method" = reference ]; then
    sim="[simulation]\nrtol = $REF_TOL\natol = $REF_TOL\nintegrator = \"cvodes_bdf\""
    expert="partitioning = \"whole\""
  fi
  [ -n "$tend" ] && sim="$sim\nt_end_ms = $tend\ndiscard_ms = 0"
  local model="[model]"
  [ -n "$mn" ] && model="[model]\nmotoneuron = \"$mn\""
  grep -Ev "^(rtol|atol|integrator|motoneuron) *=" "$cfg" |
    { [ -n "$tend" ] && grep -Ev "^(t_end_ms|discard_ms) *=" || cat; } |
    sed -e "s|^\[simulation\]|$sim|" -e "s|^\[model\]|$model|"
  # The expert table last, so that no key of the config's own tables falls into it.
  [ -z "$expert" ] || printf '\n[simulation.expert]\n%b\n' "$expert"
}

# cpu_run TOML OUT_JSON: minimum CPU seconds over REPEATS runs; features to OUT_JSON.
cpu_run() {
  local best="" t
  for _ in $(seq "$REPEATS"); do
    t=$( { /usr/bin/time -f "%U %S" "$PHASMID" simulate "$1" -o "$TMP/run.h5" -q --json > "$2"; } 2>&1 | tail -1 |
        awk '{print $1 + $2}')
    best=$(awk -v a="$t" -v b="${best:-1e9}" 'BEGIN { print (a < b ? a : b) }')
  done
  echo "$best"
}

for case in "${CASES[@]}"; do
  cfg=${case%%:*}
  mn=""; [ "$case" != "$cfg" ] && mn=${case#*:}
  variant "$cfg" "$mn" cvodes_bdf 1e-6 1 > "$TMP/startup.toml"
  startup=$(cpu_run "$TMP/startup.toml" "$TMP/startup.json")
  variant "$cfg" "$mn" reference x > "$TMP/ref.toml"
  echo "method_study: $case reference (CVODES BDF, rtol = atol = $REF_TOL, one system) ..." >&2
  ref_s=$(cpu_run "$TMP/ref.toml" "$TMP/ref.json")
  rows=$TMP/rows_${cfg}_${mn}.jsonl
  : > "$rows"
  for method in $METHODS; do
    for tol in $TOLS; do
      variant "$cfg" "$mn" "$method" "$tol" > "$TMP/v.toml"
      if s=$(cpu_run "$TMP/v.toml" "$TMP/v.json" 2> "$TMP/err"); then
        printf '{"method": "%s", "tol": %s, "cpu_s": %s, "features": %s}\n' "$method" "$tol" "$s" \
          "$(tr -d '\n' < "$TMP/v.json")" >> "$rows"
      else
        printf '{"method": "%s", "tol": %s, "failed": true}\n' "$method" "$tol" >> "$rows"
      fi
    done
  done
  /usr/bin/python3 - "$case" "$TMP/ref.json" "$rows" "$startup" "$ref_s" "${PARTITIONING:-the kind's choice}" <<'PY'
import json, sys
case, ref_path, rows_path, startup, ref_s, part = sys.argv[1:7]
startup, ref_s = float(startup), float(ref_s)
ref = {f["name"]: f for f in json.load(open(ref_path))}
gate = {"ms": 0.01, "deg": 0.01}
print(f"\n### {case} (partitioning: {part}; start-up {startup:.3f} CPU s subtracted; reference {ref_s - startup:.2f} s)\n")
print("| method | rtol = atol | run CPU s | max |d| ms | max |d| deg | max |d| 1 | matched |")
print("|---|---:|---:|---:|---:|---:|:---:|")
best = None
for line in open(rows_path):
    r = json.loads(line)
    if r.get("failed"):
        print(f"| {r['method']} | {r['tol']:g} | failed | | | | no |")
        continue
    dev = {"ms": 0.0, "deg": 0.0, "1": 0.0}
    ok = True
    for f in r["features"]:
        g = ref.get(f["name"])
        if g is None or f["value"] is None or g["value"] is None:
            continue
        d = abs(f["value"] - g["value"])
        u = f["unit"] if f["unit"] in dev else "1"
        dev[u] = max(dev[u], d)
        if u in gate and not d <= gate[u]:
            ok = False
    run = max(r["cpu_s"] - startup, 0.0)
    print(f"| {r['method']} | {r['tol']:g} | {run:.3f} | {dev['ms']:.5f} | {dev['deg']:.5f} | {dev['1']:.2e} | {'yes' if ok else 'no'} |")
    if ok and (best is None or run < best[0]):
        best = (run, r["method"], r["tol"])
if best:
    print(f"\ncheapest matched: {best[1]} at rtol = atol = {best[2]:g}, {best[0]:.3f} CPU s")
else:
    print("\nno setting matched")
PY
done
