#!/usr/bin/env bash
# The model kinds' default integration, in one run (docs/performance.md "The 2013 timings"):
#  1. 9 s of three-leg walking (configs/three_legs_tripod.toml, whose [simulation] sets no
#     solver key), spiking and rate motoneurons, phasmid at its defaults paired with a baseline
#     binary at its defaults on the same config: each round runs both in turn, so that both
#     meet the same load. Wall and CPU seconds of the whole process, minima and medians, the
#     ratio of the minima, the dissertation's 2013 timing beside them (Section 2.6: 180 s of
#     compute for 9 s of the three legs).
#  2. What the compiled right-hand side gives: the same runs with
#     [simulation.expert] compiled_rhs = false, paired with the defaults.
# The vector and matrix kernels have no switch (they are the only path); their measurement is
# bench/results/2026-12-02-kernels-against-optimised-sundials.md. The single joint against
# Brian2 is bench/bench_brian2.sh.
#
#   bash bench/bench_defaults.sh [REPEATS]          (default 5)
#   PHASMID=path (default build/phasmid). BASELINE=path: the binary to compare with; default
#   the phasmid of BASELINE_COMMIT (default f4953b8, the last version before the kinds chose
#   the fast path), built once from a git worktree into build/baseline-COMMIT/ (about ten
#   minutes on two cores).
set -euo pipefail
REPEATS=${1:-5}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PHASMID=${PHASMID:-$ROOT/build/phasmid}
BASELINE_COMMIT=${BASELINE_COMMIT:-f4953b8}
CONFIG=$ROOT/configs/three_legs_tripod.toml
[ -x "$PHASMID" ] || { echo "bench_defaults: $PHASMID not found (cmake --build build --target phasmid)" >&2; exit 1; }
if grep -Eq '^(rtol|atol|integrator) *=|^\[simulation\.expert\]' "$CONFIG"; then
  echo "bench_defaults: $CONFIG sets solver keys; this benchmark measures the kinds' defaults" >&2
  exit 1
fi

# The baseline binary: $BASELINE, or BASELINE_COMMIT's phasmid built once (with the SUNDIALS
# that scripts/setup.sh built for this tree).
baseline_binary() {
  if [ -n "${BASELINE:-}" ]; then echo "$BASELINE"; return; fi
  local dir=$ROOT/build/baseline-$BASELINE_COMMIT
  if [ ! -x "$dir/build/phasmid" ]; then
    echo "bench_defaults: building phasmid $BASELINE_COMMIT into $dir (once) ..." >&2
    [ -d "$dir/src" ] || git -C "$ROOT" worktree add -f --detach "$dir/src" "$BASELINE_COMMIT" >&2
    cmake -S "$dir/src" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release -DPHASMID_BUILD_BENCH=OFF \
      -DPHASMID_BUILD_TESTS=OFF -DPHASMID_PYTHON=OFF \
      -DSUNDIALS_DIR="$ROOT/build/sundials/install/lib/cmake/sundials" > "$dir/cmake.log" 2>&1
    cmake --build "$dir/build" -j"$(nproc)" --target phasmid > "$dir/build.log" 2>&1 ||
      { echo "bench_defaults: building the baseline failed (see $dir/build.log)" >&2; exit 1; }
  fi
  echo "$dir/build/phasmid"
}
BASE=$(baseline_binary)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The config for motoneuron model MN (spiking: as shipped; rate: [model] motoneuron = "rate"),
# optionally with [simulation.expert] lines EXPERT.
make_config() {
  local mn=$1 expert=${2:-} out=$TMP/$1${2:+_expert}.toml
  if [ "$mn" = rate ]; then sed 's/^\[model\]/[model]\nmotoneuron = "rate"/' "$CONFIG" > "$out"; else cp "$CONFIG" "$out"; fi
  [ -n "$expert" ] && printf '\n[simulation.expert]\n%s\n' "$expert" >> "$out"
  echo "$out"
}

# "wall cpu" seconds of one `simulate` of config $2 by binary $1 (the whole process; the
# compiled right-hand sides come from the cache that the warm-up run filled).
one_run() {
  local t
  t=$( { TIMEFORMAT='%R %U %S'; time "$1" simulate "$2" -o "$TMP/out.h5" -q; } 2>&1 | tail -1)
  awk '{ printf "%s %.3f\n", $1, $2 + $3 }' <<< "$t"
}

# Paired rounds of A and B (label, binary, config each); prints one table row per side and
# the ratio of the minima (B over A).
paired() {
  local la=$1 ba=$2 ca=$3 lb=$4 bb=$5 cb=$6 ra=$TMP/a.txt rb=$TMP/b.txt
  : > "$ra"; : > "$rb"
  "$ba" simulate "$ca" -o "$TMP/out.h5" -q; "$bb" simulate "$cb" -o "$TMP/out.h5" -q  # warm-up, caches
  for i in $(seq "$REPEATS"); do
    echo "bench_defaults: $la vs $lb, round $i of $REPEATS ..." >&2
    one_run "$ba" "$ca" >> "$ra"
    one_run "$bb" "$cb" >> "$rb"
  done
  /usr/bin/python3 - "$la" "$ra" "$lb" "$rb" <<'EOF'
import statistics, sys
la, ra, lb, rb = sys.argv[1:]
def load(p):
    rows = [tuple(map(float, l.split())) for l in open(p) if l.strip()]
    return [r[0] for r in rows], [r[1] for r in rows]
for label, path in ((la, ra), (lb, rb)):
    wall, cpu = load(path)
    print(f"| {label} | {min(wall):.3f} | {statistics.median(wall):.3f} | {min(cpu):.3f} | {statistics.median(cpu):.3f} |")
wa, ca = load(ra); wb, cb = load(rb)
print(f"ratio of minima, {lb} / {la}: wall {min(wb) / min(wa):.2f}, CPU {min(cb) / min(ca):.2f}")
EOF
}

echo "# bench_defaults: 9 s of three-leg walking (tripod), $REPEATS paired rounds; seconds of the whole process"
echo "# baseline: $BASE"
echo "# 2013 (dissertation Section 2.6): 180 s of compute for 9 s of the three legs"
for mn in spiking rate; do
  cfg=$(make_config "$mn")
  echo
  echo "## three legs, $mn motoneurons, each binary at its defaults"
  echo "| run | wall min | wall median | CPU min | CPU median |"
  echo "|---|---:|---:|---:|---:|"
  paired "baseline $BASELINE_COMMIT" "$BASE" "$cfg" "phasmid" "$PHASMID" "$cfg"
done
echo
echo "## the compiled right-hand side (phasmid, spiking three legs)"
echo "| run | wall min | wall median | CPU min | CPU median |"
echo "|---|---:|---:|---:|---:|"
paired "compiled_rhs = false" "$PHASMID" "$(make_config spiking 'compiled_rhs = false')" \
       "default (compiled)" "$PHASMID" "$(make_config spiking)"
