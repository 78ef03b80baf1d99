#!/usr/bin/env bash
# phasmid sweep under mpirun (3 ranks: a master and two workers, oversubscribed on small
# machines): the same HDF5 datasets, bit for bit, as the single-process run; a journal written
# under MPI resumes without it and the other way round; a worker killed with SIGKILL loses no
# finished point and --resume completes the same file; a mismatched resume is refused; verbs
# without MPI support refuse several ranks.
set -u
PHASMID="$1"; SRC="$2"
source "$SRC/tests/parallel/mpi_env.sh"   # skips without MPI; runs in a fresh temporary directory
same() {  # description, file a, file b: every dataset and group attribute under /sweep and /parameters
  if h5diff -q "$2" "$3" /sweep /sweep && h5diff -q "$2" "$3" /parameters /parameters; then ok; else bad "$1: $2 and $3 differ"; fi
}
cfg="$SRC/configs/sweep_fti_mechanics.toml"   # 20 points of milliseconds each

"$PHASMID" sweep "$cfg" -o single.h5 -j 1 -q || bad "single-process sweep"
mpirun_np3 "$PHASMID" sweep "$cfg" -o mpi.h5 -q || bad "mpirun sweep"
same "mpirun -np 3 vs one process" single.h5 mpi.h5

# interrupted under MPI, resumed without; interrupted without, resumed under MPI
mpirun_np3 "$PHASMID" sweep "$cfg" -o a.h5 -q --stop-after 7 2>err; rc=$?
[ $rc -ne 0 ] && [ ! -e a.h5 ] && [ "$(($(wc -l <a.h5.journal) - 1))" -eq 7 ] && ok || bad "MPI stop-after 7 (rc=$rc: $(cat err))"
"$PHASMID" sweep "$cfg" -o a.h5 -q --resume -j 2 && same "MPI journal resumed without MPI" single.h5 a.h5
"$PHASMID" sweep "$cfg" -o b.h5 -q --stop-after 5 -j 1 2>/dev/null
mpirun_np3 "$PHASMID" sweep "$cfg" -o b.h5 -q --resume && same "journal resumed under MPI" single.h5 b.h5

# a journal of another sweep is refused under MPI too, with one line from rank 0
"$PHASMID" sweep "$cfg" -o c.h5 -q --stop-after 3 -j 1 2>/dev/null
mpirun_np3 "$PHASMID" sweep "$cfg" -o c.h5 -q --resume --set middle.fti.b_v=13 >out 2>err; rc=$?
[ $rc -ne 0 ] && [ "$(grep -c "belongs to a different sweep" err)" -eq 1 ] && [ ! -e c.h5 ] && ok \
  || bad "mismatched resume under MPI (rc=$rc: $(cat err))"

# verbs that write one file from one process refuse several ranks (rank 0 says so, once)
mpirun_np3 "$PHASMID" simulate "$SRC/configs/fti_mechanical.toml" -o sim.h5 -q >out 2>err; rc=$?
[ $rc -ne 0 ] && [ "$(grep -c "runs in one process" err)" -eq 1 ] && [ ! -e sim.h5 ] && ok \
  || bad "simulate under mpirun (rc=$rc: $(cat err))"

# kill -9 one worker rank mid-way; Open MPI then ends the job; the journal keeps every point.
# The worker is found first and killed once 3 points are journalled, 37 of the same work each
# still to come (the sign's latency: one poll, 0.02 s). The 300 s only catch a hung job.
n=40
sed 's/t_end_ms = 3000/t_end_ms = 150000/; s/points = 5/points = 10/' "$cfg" >slow.toml   # 10 x 4 points
"$PHASMID" sweep slow.toml -o slow_single.h5 -j 1 -q || bad "single-process slow sweep"
mpirun_np3 "$PHASMID" sweep slow.toml -o k.h5 -q >/dev/null 2>&1 &
launcher=$!
victim=""; end=$((SECONDS + 300))
until [ -n "$victim" ] || ! kill -0 $launcher 2>/dev/null || [ $SECONDS -ge $end ]; do
  victim=$(rank_pid "$launcher" 1); [ -n "$victim" ] || sleep 0.02
done
until [ -z "$victim" ] || { [ -e k.h5.journal ] && [ "$(wc -l <k.h5.journal)" -ge 4 ]; }; do
  kill -0 $launcher 2>/dev/null || { bad "killed worker: the job ended before 3 points were journalled"; break; }
  [ $SECONDS -lt $end ] || { bad "killed worker: hung: fewer than 3 points journalled after 300 s"; break; }
  sleep 0.02
done
if [ -n "$victim" ]; then kill -9 "$victim"; else bad "no worker rank found to kill"; kill $launcher 2>/dev/null; fi
wait "$launcher"; rc=$?
kept=$(($(wc -l <k.h5.journal) - 1))
[ $rc -ne 0 ] && [ ! -e k.h5 ] && [ "$kept" -ge 3 ] && [ "$kept" -lt $n ] && ok \
  || bad "killed worker: rc=$rc, $kept points journalled, k.h5 $( [ -e k.h5 ] && echo exists || echo absent)"
mpirun_np3 "$PHASMID" sweep slow.toml -o k.h5 -q --resume 2>err && same "resumed after a killed worker" slow_single.h5 k.h5 \
  || bad "resume after a killed worker: $(cat err)"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
