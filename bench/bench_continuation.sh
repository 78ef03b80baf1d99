#!/usr/bin/env bash
# Cost per point of `phasmid continue` against `phasmid sweep` at the same parameter values
# (docs/performance.md "Continuation"): the continuation pays one transient, then Newton
# shooting with the monodromy per point; every sweep point pays its own transient
# (transient_ms of the continuation) plus the cycles its features average over.
# Usage: bench/bench_continuation.sh [PHASMID] [CONFIG] [START END]
#   default: build/phasmid configs/continue_single_joint_gapp.toml 0.1 0.2
# Prints CPU seconds (user + sys, one thread each) and the ratio sweep / continuation per point.
set -eu
PHASMID=${1:-build/phasmid}
CONFIG=${2:-configs/continue_single_joint_gapp.toml}
START=${3:-0.1}
END=${4:-0.2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed -E "s/^range = .*/range = [$START, $END]/" "$CONFIG" >"$tmp/cont.toml"
cpu() { /usr/bin/time -f "%U %S" -o "$tmp/time" "$@" >/dev/null 2>&1; awk '{print $1 + $2}' "$tmp/time"; }
c_cpu=$(OMP_NUM_THREADS=1 cpu "$PHASMID" continue "$tmp/cont.toml" -q -o "$tmp/cont.h5")
param=$(/usr/bin/python3 -c "import h5py; print(h5py.File('$tmp/cont.h5','r')['continuation'].attrs['parameter'])")
values=$(/usr/bin/python3 -c "import h5py; print(', '.join(repr(float(v)) for v in h5py.File('$tmp/cont.h5','r')['continuation/parameter'][:]))")
n=$(/usr/bin/python3 -c "import h5py; print(len(h5py.File('$tmp/cont.h5','r')['continuation/parameter']))")
transient=$(sed -nE 's/^transient_ms = ([0-9.]+).*/\1/p' "$tmp/cont.toml")
# The sweep: the transient, then 3000 ms of cycles for the features (about six periods).
sed -E '/^\[continuation/,$d' "$CONFIG" >"$tmp/sweep.toml"
cat >>"$tmp/sweep.toml" <<TOML
[sweep]
design = "grid"
t_end_ms = $(echo "$transient + 3000" | bc)
discard_ms = $transient
[[sweep.parameter]]
name = "$param"
values = [$values]
TOML
s_cpu=$(cpu "$PHASMID" sweep "$tmp/sweep.toml" -q -j 1 -o "$tmp/sweep.h5")
echo "points: $n ($param from $START toward $END)"
echo "continuation: $c_cpu CPU s, $(echo "scale=3; $c_cpu / $n" | bc) s per point"
echo "sweep:        $s_cpu CPU s, $(echo "scale=3; $s_cpu / $n" | bc) s per point (transient $transient ms each)"
echo "ratio sweep / continuation per point: $(echo "scale=2; $s_cpu / $c_cpu" | bc)"
