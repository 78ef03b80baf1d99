#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang++ with AddressSanitizer and UBSan) in build-asan
# (scripts/sanitizer_build.sh) and runs each for SECONDS (default 60), starting from its seed
# corpus fuzz/corpus/<target>/. A crash, leak, timeout or out-of-memory input is copied into
# fuzz/regressions/<target>/ (once committed with its fix, ctest fuzz_replay_<target> replays
# it) and the script fails after running the remaining targets. docs/reliability.md, "Fuzzing".
# Usage: scripts/run_fuzz.sh [SECONDS]; FUZZ_TARGETS="config journal" runs only those.
# FUZZ_SEED (default 1) fixes libFuzzer's random seed so that a CI failure can be reproduced
# with the same command; FUZZ_SEED=0 lets libFuzzer pick one (for exploratory runs).
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
SEED=${FUZZ_SEED:-1}
TARGETS=${FUZZ_TARGETS:-$(ls fuzz/targets | sed 's/\.cpp$//')}

source scripts/sanitizer_build.sh
configure_sanitizer_build
start=$(date +%s)
cmake --build "$SANITIZER_BUILD" -j"$(nproc)" --target $(printf 'fuzz_%s ' $TARGETS) >"$SANITIZER_BUILD/fuzz-build.log" 2>&1 ||
  { tail -30 "$SANITIZER_BUILD/fuzz-build.log"; exit 1; }
echo "run_fuzz: build $(( $(date +%s) - start )) s"

export OMP_NUM_THREADS=1
fail=0
for t in $TARGETS; do
  work=$SANITIZER_BUILD/fuzz/run/$t
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  start=$(date +%s)
  # New inputs go to the first (scratch) corpus directory; the seeds in the repo stay as they are.
  # Full allocation stacks for the HDF5 reader: libhdf5 has no frame pointers, and its
  # suppression in tests/sanitizers/lsan.supp matches a frame the fast unwinder cannot see.
  asan=$ASAN_OPTIONS
  case $t in h5_*) asan+=:fast_unwind_on_malloc=0 ;; esac
  if ASAN_OPTIONS=$asan "$SANITIZER_BUILD/fuzz/fuzz_$t" -max_total_time="$SECONDS_EACH" -seed="$SEED" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
       -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" "fuzz/corpus/$t" \
       >"$work/log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || echo '?')
    echo "run_fuzz: $t ok ($runs inputs in $(( $(date +%s) - start )) s)"
  else
    fail=1
    mkdir -p "fuzz/regressions/$t"
    # slow-unit-* are only slow (under -timeout): not kept
    cp "$work"/artifacts/{crash,leak,timeout,oom}-* "fuzz/regressions/$t/" 2>/dev/null || true
    echo "run_fuzz: $t FAILED after $(( $(date +%s) - start )) s; input(s) kept in fuzz/regressions/$t/:" \
         "$(ls "$work/artifacts" | grep -v "^slow-unit" | tr '\n' ' ')" >&2
    grep -m1 -E 'ERROR: |runtime error|==ERROR|deadly signal|uncaught exception|terminate called' "$work/log" >&2 || true
    echo "run_fuzz: full log in $work/log" >&2
  fi
done
exit $fail
