#!/usr/bin/env bash
# MPI benchmark (docs/performance.md "Threads, sweeps and MPI"): wall time of the 16-point three-leg sweep
# bench/sweep_three_legs_16.toml (rate motoneurons) with one process, with
# `mpirun -np 3` (a master and two workers of one thread) and with 2 OpenMP threads, as ratios
# to one process; the master's cost per task with a trivial evaluator; and the projected
# parallel efficiency at 64/256/1024 ranks from the measured per-point costs.
#   bash bench/bench_mpi.sh [BUILD_DIR]        (default: build)
#   MOTONEURON=spiking bash bench/bench_mpi.sh  the same sweep with the dissertation's spiking
#                                               motoneurons (~8 s per point instead of ~0.6 s)
set -euo pipefail
SRC="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$SRC/build}"
PHASMID="$BUILD/phasmid"; BENCH="$BUILD/bench/bench_mpi"
CFG="$SRC/bench/sweep_three_legs_16.toml"
[ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMP_NUM_THREADS=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
if [ "${MOTONEURON:-rate}" != rate ]; then
  sed "s/^motoneuron = \"rate\"/motoneuron = \"${MOTONEURON}\"/" "$CFG" >"$tmp/sweep.toml"
  CFG="$tmp/sweep.toml"
fi
wall() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg) on $(getconf _NPROCESSORS_ONLN) cores"
t1=$(wall "$PHASMID" sweep "$CFG" -o "$tmp/one.h5" -j 1 -q)
tm=$(wall mpirun --oversubscribe -np 3 "$PHASMID" sweep "$CFG" -o "$tmp/mpi.h5" -q)
to=$(wall "$PHASMID" sweep "$CFG" -o "$tmp/omp.h5" -j 2 -q)
h5diff -q "$tmp/one.h5" "$tmp/mpi.h5" /sweep /sweep && h5diff -q "$tmp/one.h5" "$tmp/omp.h5" /sweep /sweep \
  && echo "outputs: identical /sweep datasets in all three runs"
printf '16-point three-leg sweep: 1 process %.2f s | mpirun -np 3 (2 workers) %.2f s = %.2fx | OpenMP 2 threads %.2f s = %.2fx\n' \
  "$t1" "$tm" "$(echo "$t1 / $tm" | bc -l)" "$to" "$(echo "$t1 / $to" | bc -l)"
master=$(mpirun --oversubscribe -np 3 "$BENCH" master 20000 8)
echo "$master"
us=$(echo "$master" | sed -n 's/.*, \([0-9.]*\) us per task/\1/p')
"$BENCH" costs "$CFG" "$us"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
