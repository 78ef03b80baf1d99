#!/usr/bin/env bash
# What sensitivities over all of a model's parameters cost, as ratios to one plain 9 s run of
# the same model in the same script (docs/sensitivity.md, "What a sensitivity run costs"):
#   - steady cycle (mode = "steady_cycle": transient, Newton shooting, the implicit-function
#     step, the features on the converged cycle), every parameter and every feature, on one
#     thread, and its wall time on one and two threads (chunks of parameters, -j);
#   - transient (mode = "transient": the 9 s run with forward sensitivities of every parameter,
#     features over [1.5 s, 9 s]), the same parameters.
# Models: the single FTi joint with rate motoneurons; with FULL=1 also the middle leg with rate
# motoneurons, whose all-parameter runs take minutes; with
# SPIKING=1 the spiking single joint's transient mode on one and two threads.
#
#   bash bench/bench_cycle_sensitivity.sh [REPEATS]     (default 3; PHASMID=path, default build/phasmid)
set -euo pipefail
REPEATS=${1:-3}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PHASMID=${PHASMID:-$ROOT/build/phasmid}
[ -x "$PHASMID" ] || { echo "bench_cycle_sensitivity: $PHASMID not found (cmake --build build --target phasmid)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The [model] section of shipped config SHIPPED with rate motoneurons, running 9 s, with a
# [sensitivity] section of mode MODE over every parameter.
make_config() {
  local name=$1 shipped=$2 mode=$3 out=$TMP/$1_$3.toml
  sed -n '/^\[model\]/,/^\[/p' "$ROOT/configs/$shipped" | grep -v '^\[' | grep -v '^motoneuron' > "$TMP/model.txt"
  { echo '[model]'; cat "$TMP/model.txt"; echo 'motoneuron = "rate"'; } > "$out"
  printf '\n[simulation]\nt_end_ms = 9000\noutput_dt_ms = 1.0\ndiscard_ms = 1500\n\n' >> "$out"
  printf '[sensitivity]\nmode = "%s"\ntrajectory = false\ntransient_ms = 4000\nmax_period_ms = 1000\n' "$mode" >> "$out"
  echo "$out"
}

# CPU seconds (user + system; WHAT=wall: wall seconds) of the whole process, the least of
# REPEATS runs.
cpu_min() {
  local best=""
  for _ in $(seq "$REPEATS"); do
    local t
    t=$( { TIMEFORMAT='%R %U %S'; time "$@" > /dev/null; } 2>&1 | tail -1)
    t=$(awk -v w="${WHAT:-cpu}" '{ printf "%.3f", w == "wall" ? $1 : $2 + $3 }' <<< "$t")
    if [ -z "$best" ] || awk -v a="$t" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$t; fi
  done
  echo "$best"
}

row() {  # NAME SHIPPED-CONFIG
  local name=$1 model=$2 plain steady transient np
  local cs ct
  cs=$(make_config "$name" "$model" steady_cycle)
  ct=$(make_config "$name" "$model" transient)
  echo "bench_cycle_sensitivity: $name ..." >&2
  plain=$(cpu_min "$PHASMID" simulate "$cs" -o "$TMP/plain.h5" -q)
  steady=$(cpu_min "$PHASMID" sensitivity "$cs" -o "$TMP/steady.h5" -q -j 1)
  transient=$(cpu_min "$PHASMID" sensitivity "$ct" -o "$TMP/transient.h5" -q)
  wall1=$(WHAT=wall cpu_min "$PHASMID" sensitivity "$cs" -o "$TMP/steady.h5" -q -j 1)
  wall2=$(WHAT=wall cpu_min "$PHASMID" sensitivity "$cs" -o "$TMP/steady.h5" -q -j 2)
  np=$(/usr/bin/python3 -c "import h5py,sys; print(len(h5py.File(sys.argv[1])['/sensitivity/parameters']))" "$TMP/steady.h5")
  awk -v n="$name" -v np="$np" -v p="$plain" -v s="$steady" -v t="$transient" -v w1="$wall1" -v w2="$wall2" \
    'BEGIN { printf "| %s | %d | %.3f | %.3f | %.1f | %.3f | %.1f | %.2f / %.2f = %.2f |\n", n, np, p, s, s / p, t, t / p, w1, w2, w1 / w2 }'
}

echo "# bench_cycle_sensitivity: CPU seconds (least of $REPEATS), ratios to one plain 9 s run of the same model"
echo "| model | parameters | plain 9 s run | steady cycle, 1 thread | ratio | transient 9 s | ratio | steady cycle wall, 1 / 2 threads |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
row "single joint (FTi), rate MN" single_joint_fti.toml
# The three legs have no isolated cycle to differentiate: their legs' relative phases are
# neutral (docs/sensitivity.md), and the steady-cycle mode refuses them.
if [ "${FULL:-0}" = 1 ]; then
  row "middle leg, rate MN" middle_leg_forward.toml
fi
# The spiking single joint, whose orbit does not close: the transient mode over all its
# parameters, wall seconds on one and two threads (chunks of parameters, -j).
if [ "${SPIKING:-0}" = 1 ]; then
  sed -e '/^motoneuron/d' -e 's/^mode = .*/mode = "transient"/' "$TMP/single joint (FTi), rate MN_transient.toml" > "$TMP/spiking.toml"
  echo "bench_cycle_sensitivity: spiking single joint, transient ..." >&2
  w1=$(WHAT=wall cpu_min "$PHASMID" sensitivity "$TMP/spiking.toml" -o "$TMP/s.h5" -q -j 1)
  w2=$(WHAT=wall cpu_min "$PHASMID" sensitivity "$TMP/spiking.toml" -o "$TMP/s.h5" -q -j 2)
  echo
  echo "spiking single joint, transient mode, all parameters: wall $w1 s on 1 thread, $w2 s on 2 ($(awk -v a="$w1" -v b="$w2" 'BEGIN { printf "%.2f", a / b }')x)"
fi
