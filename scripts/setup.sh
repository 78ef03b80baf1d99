#!/usr/bin/env bash
# Installs phasmid's Debian dependencies (when missing) and builds it into ./build.
# Idempotent: a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config
  libsundials-dev libceres-dev libnlopt-cxx-dev libnlopt-dev libeigen3-dev libhdf5-dev
  libtomlplusplus-dev libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev fonts-liberation
  libopenmpi-dev openmpi-bin hdf5-tools time
  python3-dev pybind11-dev python3-numpy python3-h5py python3-pytest python3-nbclient python3-ipykernel
  python3-matplotlib
  libmatio-dev python3-scipy
)
# Report tests render the HTML reports in a real browser.
if [ "${PHASMID_WITH_BROWSER:-1}" = 1 ]; then PACKAGES+=(chromium); fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "phasmid setup: installing ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# SUNDIALS from Debian's source package, built with optimisation (Debian's binary package is
# -O0; scripts/build_sundials.sh says why). Without it, Debian's libraries: same numbers, slower.
if bash scripts/build_sundials.sh; then
  SUNDIALS_ARG=(-DSUNDIALS_DIR="$PWD/build/sundials/install/lib/cmake/sundials")
else
  echo "phasmid setup: WARNING: no optimised SUNDIALS build; using Debian's -O0 libraries (same numbers, slower)" >&2
  SUNDIALS_ARG=(-USUNDIALS_DIR)
fi
# A compiler cache, when the machine has one, makes a second checkout's build a matter of
# linking (the base directory makes its entries independent of where the tree is checked out).
LAUNCHER=()
if command -v ccache >/dev/null; then
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # The precompiled headers (CMakeLists.txt, PHASMID_PCH) are cached only with these.
  export CCACHE_BASEDIR="$PWD" CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${SUNDIALS_ARG[@]}" "${LAUNCHER[@]}" >/dev/null
cmake --build build -j"$(nproc)"

# The Python module (docs/python.md): a .pth file in Debian's Python's site-packages points
# at build/python, so `/usr/bin/python3 -c "import phasmid"` imports this build (and every
# rebuild) from anywhere; delete that one file to uninstall.
if ls build/python/phasmid/_core*.so >/dev/null 2>&1; then
  site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
  pth="$site/phasmid.pth"
  if [ "$(cat "$pth" 2>/dev/null)" != "$PWD/build/python" ]; then
    SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
    $SUDO mkdir -p "$site"
    echo "$PWD/build/python" | $SUDO tee "$pth" >/dev/null
    echo "phasmid setup: $pth -> $PWD/build/python (import phasmid)" >&2
  fi
fi
