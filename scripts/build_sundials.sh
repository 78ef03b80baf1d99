#!/usr/bin/env bash
# Builds Debian's own SUNDIALS source package (the version of the installed libsundials-dev,
# with Debian's patches) with optimisation, into build/sundials/install, for phasmid to link.
#
# Why: Debian 12's binary packages are compiled without optimisation. debian/rules passes
# -DCMAKE_C_FLAGS=-fcommon, which replaces the -O2 of dpkg-buildflags, so CVODES' and
# ARKODE's step, error-test, Newton and interpolation code runs as -O0 code (docs/performance.md).
# The same source at -O2 (no -march, no fast-math: the same IEEE operations in the same order)
# gives bit-identical trajectories.
#
# Idempotent: skips the build when build/sundials/install holds this version already.
# Exit status 0 = the optimised build is in place; non-zero = it could not be made (setup.sh
# then uses Debian's binary libraries: the same numbers, slower).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD/build/sundials
PREFIX=$ROOT/install
CFLAGS_OPT="-O2 -fcommon"
VERSION=$(dpkg-query -W -f='${source:Version}' libsundials-dev 2>/dev/null) || {
  echo "build_sundials: libsundials-dev is not installed" >&2; exit 1; }
STAMP="sundials $VERSION, CFLAGS $CFLAGS_OPT"
if [ "$(cat "$PREFIX/.phasmid-stamp" 2>/dev/null)" = "$STAMP" ]; then exit 0; fi

SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
# apt-get source needs deb-src entries: the machine's Debian sources, as source lists.
add_deb_src() {
  local d=/etc/apt/sources.list.d
  if [ -f $d/debian.sources ] && ! grep -qs '^Types:.*deb-src' $d/*.sources; then
    sed 's/^Types: deb$/Types: deb-src/' $d/debian.sources | $SUDO tee $d/phasmid-deb-src.sources >/dev/null
  elif [ -f /etc/apt/sources.list ] && ! grep -qs '^deb-src ' /etc/apt/sources.list $d/*.list; then
    grep '^deb ' /etc/apt/sources.list | sed 's/^deb /deb-src /' | $SUDO tee $d/phasmid-deb-src.list >/dev/null
  fi
  $SUDO apt-get update -qq
}

rm -rf "$ROOT/src" "$ROOT/build" "$PREFIX"
mkdir -p "$ROOT/src"
cd "$ROOT/src"
chmod 777 .  # apt's download user writes here
fetch() { apt-get source --download-only -qq "$@" >/dev/null 2>&1; }
if ! fetch "sundials=$VERSION"; then
  add_deb_src
  fetch "sundials=$VERSION" || fetch sundials || {
    echo "build_sundials: apt-get source sundials failed (no deb-src reachable)" >&2; exit 1; }
fi
dpkg-source -x --no-check sundials_*.dsc sundials >/dev/null

echo "build_sundials: building SUNDIALS $VERSION (CVODES, ARKODE) with $CFLAGS_OPT ..." >&2
cmake -S sundials -B "$ROOT/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS="$CFLAGS_OPT" \
  -DCMAKE_C_FLAGS_RELEASE="" -DCMAKE_INSTALL_PREFIX="$PREFIX" \
  -DBUILD_SHARED_LIBS=ON -DBUILD_STATIC_LIBS=OFF \
  -DBUILD_ARKODE=ON -DBUILD_CVODES=ON -DBUILD_CVODE=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
  -DENABLE_KLU=ON -DKLU_INCLUDE_DIR=/usr/include/suitesparse \
  -DKLU_LIBRARY_DIR="/usr/lib/$(dpkg-architecture -qDEB_HOST_MULTIARCH)" \
  -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_ENABLE_CXX=OFF -DEXAMPLES_INSTALL=OFF >"$ROOT/configure.log" 2>&1 ||
  { tail -20 "$ROOT/configure.log" >&2; exit 1; }
cmake --build "$ROOT/build" -j"$(nproc)" >"$ROOT/build.log" 2>&1 || { tail -20 "$ROOT/build.log" >&2; exit 1; }
cmake --install "$ROOT/build" >"$ROOT/install.log" 2>&1 || { tail -20 "$ROOT/install.log" >&2; exit 1; }
rm -rf "$ROOT/build" "$ROOT/src"
echo "$STAMP" > "$PREFIX/.phasmid-stamp"
