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
  libopenmpi-dev openmpi-bin hdf5-tools
  python3-h5py  # the adversarial corpus crafts damaged HDF5 inputs with it (tests/adversarial)
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

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
