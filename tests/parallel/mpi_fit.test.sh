#!/usr/bin/env bash
# phasmid fit under mpirun (3 ranks): multistart (one local optimisation per task) and a
# profile likelihood (its two halves as tasks) give the same /fit datasets, bit for bit, as the
# single-process run. Left out of the comparison: what measures time (the wall_seconds
# attributes, Ceres' report) and the run attributes (command, created); the summary text is
# compared with its timing removed.
set -u
PHASMID="$1"; SRC="$2"
source "$SRC/tests/parallel/mpi_env.sh"   # skips without MPI; runs in a fresh temporary directory
cfg="$SRC/configs/fit_fti_section31.toml"
args=(--multistart 6 --profile middle.fti.k_F.flexion --profile middle.fti.k_E.extension -q)
"$PHASMID" fit "$cfg" "${args[@]}" -o single.h5 || bad "single-process fit"
mpirun_np3 "$PHASMID" fit "$cfg" "${args[@]}" -o mpi.h5 || bad "mpirun fit (exit $?)"
if h5diff -q --exclude-path /fit/report --exclude-path /fit/summary --exclude-attribute / \
     --exclude-attribute /fit --exclude-attribute /trajectory single.h5 mpi.h5; then ok; else bad "/fit datasets differ"; fi
for d in /fit/multistart/final_cost /fit/profile/middle.fti.k_F.flexion/cost /fit/profile/middle.fti.k_E.extension/delta_chi2; do
  [ "$(h5dump -d "$d" single.h5 | wc -l)" -gt 5 ] && ok || bad "$d missing"
done
attrs() { h5dump -A -g /fit "$1" | tail -n +2 | awk '/ATTRIBUTE "wall_seconds"/ {skip = 7} skip {skip--; next} 1'; }
attrs single.h5 | grep -q "ATTRIBUTE \"iterations\"" && [ "$(attrs single.h5)" = "$(attrs mpi.h5)" ] && ok || bad "/fit attributes (other than wall_seconds) differ"
summary() { h5dump -d /fit/summary "$1" | tail -n +2 | sed 's/ in [0-9.e+-]* s$//'; }
summary single.h5 | grep -q "multistart: 6 starts" && [ "$(summary single.h5)" = "$(summary mpi.h5)" ] && ok || bad "/fit/summary differs beyond its timing"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
