#!/usr/bin/env bash
# phasmid gsa under mpirun (3 ranks): the design points are handed out by the sweep engine's MPI
# executor and rank 0 analyses; /sweep and /gsa equal the single-process run's bit for bit, and
# a journal written under MPI resumes without it.
set -u
PHASMID="$1"; SRC="$2"
source "$SRC/tests/parallel/mpi_env.sh"   # skips without MPI; runs in a fresh temporary directory
same() {
  if h5diff -q "$2" "$3" /sweep /sweep && h5diff -q "$2" "$3" /gsa /gsa; then ok; else bad "$1: $2 and $3 differ"; fi
}
sed 's/^N = 8192/N = 256/' "$SRC/configs/gsa_ishigami.toml" >ishigami.toml   # 2048 points
"$PHASMID" gsa ishigami.toml -o single.h5 -j 1 -q || bad "single-process gsa"
mpirun_np3 "$PHASMID" gsa ishigami.toml -o mpi.h5 -q || bad "mpirun gsa"
same "mpirun -np 3 vs one process" single.h5 mpi.h5
mpirun_np3 "$PHASMID" gsa ishigami.toml -o a.h5 -q --stop-after 700 2>err; rc=$?
[ $rc -ne 0 ] && [ ! -e a.h5 ] && ok || bad "MPI stop-after (rc=$rc: $(cat err))"
"$PHASMID" gsa ishigami.toml -o a.h5 -q --resume -j 2 && same "MPI journal resumed without MPI" single.h5 a.h5
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
