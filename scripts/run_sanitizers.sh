#!/usr/bin/env bash
# Runs the tests of file handling and run machinery, the script tests (the CLI on hostile input)
# and every shipped example (configs/*.toml through
# `simulate`, `features` and `report`, shortened to t_end_ms = 600) in the AddressSanitizer +
# UndefinedBehaviorSanitizer build build-asan (scripts/sanitizer_build.sh). Any sanitizer
# report, a leak included, fails the run. docs/reliability.md, "Sanitizers".
# Usage: scripts/run_sanitizers.sh. With PHASMID_DEADLINE (seconds since the epoch; .ci/run sets
# it) the tests (in chunks) and the examples stop when it is near, and the run says how many
# were left out.
set -euo pipefail
cd "$(dirname "$0")/.."

# The test executables built and run here: those of the code that reads and writes files and
# parses input (configs, tables, journals, HDF5, reports), of the run machinery around the
# solver (schedules, interrupts, the stepper's buffers, threads) and of the model registry. The
# numerical tests (integrators' accuracy, sensitivities, fits, gaits) run in the Release
# suite; under the sanitizers they would cost more build time than the CI budget has (each
# test file takes ~20 CPU s to compile with clang and ASan) for code the examples below and
# the script tests (the CLI on hostile input, through this build's phasmid) already run.
SANITIZER_EXES="test_h5_file test_h5_heap_check test_input_output_checks test_trajectory_stream
  test_sweep_run test_sweep_design test_gsa_h5 test_gsa_resolution test_report test_features
  test_feature_catalogue test_model_kinds test_executor test_fit_inputs test_fit_h5
  test_cruse1980_config test_simroach2_config test_interrupt test_command_schedule
  test_dopri_session test_continuation test_output_lock test_sweep_resume"
# Tests left out of the executables that are built: the browser renderings (Chromium is not
# instrumented and dominates their time), the examples test (replaced by the shortened
# examples below), MPI (build-asan has none), the demo, the GSA command-line test, the two
# writers' pairs and the synthetic recording fits and PEtab round trip (minutes of simulation under ASan, past
# ctest's 900 s limit for the fit; the Release suite runs them; the lock's own tests and the
# recording readers' tests run here), and the long runs among the trajectory-stream comparisons.
SLOW_TESTS='ReportRender\.|script_configs|script_demo|script_mpi|script_gsa_cli|script_writers|script_fit_recording|script_fit_conditions|script_petab|_NOT_BUILT'
SLOW_TESTS+='|TrajectoryStream\.(CurveWalkingBodyPath|TriggeredCommandsPartitioned|ThreeLegsSixLegPatternPartitioned)'

source scripts/sanitizer_build.sh
configure_sanitizer_build
B=$SANITIZER_BUILD
targets=(phasmid $SANITIZER_EXES fuzz_replay_all)
start=$(date +%s)
cmake --build "$B" -j"$(nproc)" --target "${targets[@]}" >"$B/build.log" 2>&1 || { tail -30 "$B/build.log"; exit 1; }
echo "run_sanitizers: build (${#targets[@]} targets) $(( $(date +%s) - start )) s"

# Full allocation stacks: libhdf5 has no frame pointers, and its suppression in
# tests/sanitizers/lsan.supp matches a frame the fast unwinder cannot see.
export ASAN_OPTIONS=$ASAN_OPTIONS:fast_unwind_on_malloc=0
export OMP_NUM_THREADS=2
fail=0
start=$(date +%s)
# In chunks of 20 tests, so that with PHASMID_DEADLINE the tests stop between two chunks when
# less than 60 s are left; the run says how many were not run (a chunk's failures still fail it).
total=$(ctest --test-dir "$B" -N | sed -n 's/^Total Tests: //p')
ran=0
for ((first = 1; first <= total; first += 20)); do
  if [ -n "${PHASMID_DEADLINE:-}" ] && [ $((PHASMID_DEADLINE - $(date +%s))) -lt 60 ]; then
    echo "run_sanitizers: the time budget is used: tests $first to $total (of $total, before the filter) not run"
    break
  fi
  ctest --test-dir "$B" --output-on-failure -j"$(nproc)" -I "$first,$((first + 19))" -E "$SLOW_TESTS" >"$B/ctest_chunk.log" 2>&1 || {
    fail=1; cat "$B/ctest_chunk.log"; }
  ran=$((ran + $(grep -cE '^ *[0-9]+/[0-9]+ Test +#' "$B/ctest_chunk.log" || true)))
done
echo "run_sanitizers: $ran tests $(( $(date +%s) - start )) s ($([ $fail -eq 0 ] && echo all passed || echo FAILURES above))"

# The shipped examples, shortened: the copies keep their directory layout, so paths relative
# to configs/ (../datasets) still resolve.
start=$(date +%s)
ex=$B/examples
rm -rf "$ex"
mkdir -p "$ex/configs"
ln -s "$PWD/datasets" "$ex/datasets"
n=0
total=$(ls configs/*.toml | wc -l)
for cfg in configs/*.toml; do
  if [ -n "${PHASMID_DEADLINE:-}" ] && [ $((PHASMID_DEADLINE - $(date +%s))) -lt 30 ]; then
    echo "run_sanitizers: the time budget is used: $((total - n)) of $total examples not run"
    break
  fi
  name=$(basename "$cfg" .toml)
  awk -v T=600 '
    /^\[/ { if (sim && !done) { print "t_end_ms = " T; done = 1 } sim = ($0 ~ /^\[simulation\][ \t]*(#.*)?$/) }
    sim && /^t_end_ms[ \t]*=/ { print "t_end_ms = " T; done = 1; next }
    sim && /^discard_ms[ \t]*=/ { print "discard_ms = 0"; next }
    { print }
    END { if (sim && !done) print "t_end_ms = " T }' "$cfg" >"$ex/configs/$name.toml"
  n=$((n + 1))
  if ! "$B/phasmid" simulate "$ex/configs/$name.toml" -q -o "$ex/$name.h5" 2>"$ex/$name.err" ||
     ! "$B/phasmid" features "$ex/$name.h5" --json >/dev/null 2>>"$ex/$name.err" ||
     ! "$B/phasmid" report "$ex/$name.h5" -o "$ex/$name.html" >/dev/null 2>>"$ex/$name.err"; then
    echo "run_sanitizers: example $name FAILED:" >&2
    head -40 "$ex/$name.err" >&2
    fail=1
  fi
done
echo "run_sanitizers: $n of $total examples $(( $(date +%s) - start )) s"
exit $fail
