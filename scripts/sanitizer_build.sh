# Sourced by scripts/run_sanitizers.sh and scripts/run_fuzz.sh: configures build-asan, the one
# instrumented build both use (docs/reliability.md, "Sanitizers"). clang++ with
# AddressSanitizer, UndefinedBehaviorSanitizer (whose clang group includes
# float-cast-overflow) and libFuzzer's coverage instrumentation, so the fuzz targets and the
# sanitizer test suite share one compilation of the library. MPI off: Open MPI's runtime is
# uninstrumented and keeps allocations until exit (suppressions of its internals); the Release
# suite tests the MPI paths (script_mpi_*). Python off: the module would need the ASan runtime
# preloaded into the interpreter, and python_api would otherwise import the Release module
# (the .pth file scripts/setup.sh installs) and compare it bit for bit with this build's CLI,
# whose exponentials are not libmvec's (clang).
SANITIZER_BUILD=build-asan

configure_sanitizer_build() {
  local packages=(clang libclang-rt-14-dev libomp-dev) missing=() p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "phasmid: installing ${missing[*]}" >&2
    local sudo=""; [ "$(id -u)" = 0 ] || sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache) && export CCACHE_BASEDIR="$PWD"
  cmake -S . -B "$SANITIZER_BUILD" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    "${launcher[@]}" -DPHASMID_FUZZ=ON -DPHASMID_BUILD_TESTS=ON -DPHASMID_BUILD_BENCH=OFF -DPHASMID_WITH_MPI=OFF -DPHASMID_PYTHON=OFF \
    "-DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -g" >/dev/null
}

# Any sanitizer report fails; a leak is a failure; known third-party leaks only in the file.
# allocator_may_return_null: a size read from a damaged file (HDF5 allocates what its headers
# declare) gets NULL, which the library reports as an error, instead of ending the process.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0
