#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang++ with AddressSanitizer and UBSan) into
# build-fuzz and runs each for SECONDS (default 60), starting from its seed corpus
# fuzz/corpus/<target>/. A crash, leak, timeout or out-of-memory is copied into
# fuzz/regressions/<target>/ (replayed from then on by ctest fuzz_replay_<target>) and the
# script fails after running the remaining targets. docs/reliability.md, "Fuzzing".
# Usage: scripts/run_fuzz.sh [SECONDS]; FUZZ_TARGETS="config journal" runs only those.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
TARGETS=${FUZZ_TARGETS:-config kinematic_csv parameter_table journal h5_input}

PACKAGES=(clang libclang-rt-14-dev libomp-dev)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "run_fuzz: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

LAUNCHER=()
command -v ccache >/dev/null && LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# MPI off: the readers never touch it, and Open MPI's runtime leaks at exit (LeakSanitizer).
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "${LAUNCHER[@]}" -DPHASMID_FUZZ=ON -DPHASMID_BUILD_TESTS=OFF -DPHASMID_BUILD_BENCH=OFF -DPHASMID_WITH_MPI=OFF \
  "-DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -g" >/dev/null
start=$(date +%s)
cmake --build build-fuzz -j"$(nproc)" --target $(printf 'fuzz_%s ' $TARGETS) >/dev/null
echo "run_fuzz: build $(( $(date +%s) - start )) s"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export OMP_NUM_THREADS=1
fail=0
for t in $TARGETS; do
  work=build-fuzz/run/$t
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  start=$(date +%s)
  # New inputs go to the first (scratch) corpus directory; the seeds in the repo stay as they are.
  if build-fuzz/fuzz/fuzz_$t -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
       -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" "fuzz/corpus/$t" \
       >"$work/log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || echo '?')
    echo "run_fuzz: $t ok ($runs inputs in $(( $(date +%s) - start )) s)"
  else
    fail=1
    mkdir -p "fuzz/regressions/$t"
    cp "$work"/artifacts/* "fuzz/regressions/$t/" 2>/dev/null || true
    echo "run_fuzz: $t FAILED after $(( $(date +%s) - start )) s; input(s) kept in fuzz/regressions/$t/:" \
         "$(ls "$work/artifacts" | tr '\n' ' ')" >&2
    grep -m1 -E 'ERROR: |runtime error|==ERROR|deadly signal|uncaught exception|terminate called' "$work/log" >&2 || true
    echo "run_fuzz: full log in $work/log" >&2
  fi
done
exit $fail
