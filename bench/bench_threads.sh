#!/usr/bin/env bash
# The three legs' partitioned run on 1 and 2 threads ([simulation] threads): 9 s of
# walking at the kinds' defaults (spiking: Dormand-Prince per joint at 1e-6, phasmid's dopri5 or
# SPIKING_INTEGRATOR; rate: CVODES BDF per joint at 1e-7), wall and CPU seconds (best of
# BENCH_REPEATS, default 3) and the ratios against the sequential run (threads = 1) of the
# same script, with the load average before each row: a second thread only helps while a
# second core is free. A variant "... @W" runs in windows of W ms instead of WINDOW_MS.
#
#   bash bench/bench_threads.sh [WINDOW_MS=1]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BENCH=${BENCH:-$ROOT/build/bench/bench_walking}
WINDOW=${1:-1}
export BENCH_REPEATS=${BENCH_REPEATS:-3}
SPIKING_INTEGRATOR=${SPIKING_INTEGRATOR:-dopri5}  # the kind's default
[ -x "$BENCH" ] || { echo "bench_threads: $BENCH not found (cmake --build build --target bench_walking)" >&2; exit 1; }
printf "# bench_threads: 9000 ms of the three legs, best of %s, window %s ms, %s\n" "$BENCH_REPEATS" "$WINDOW" "$(date -u +%FT%TZ)"
printf "%-8s %-30s %7s %8s %8s %8s %9s %9s  %s\n" mn variant threads wall_s cpu_s steps wall/seq cpu/seq load
for mn in spiking rate; do
  if [ $mn = spiking ]; then integ=$SPIKING_INTEGRATOR tol=1e-6; else integ=cvodes_bdf tol=1e-7; fi
  variants=("default" "default @0.25")
  [ $mn = rate ] && variants+=("1=1e-6,mV=1e-5" "1=1e-6,mV=1e-5 @0.25")
  for v in "${variants[@]}"; do
    seq_wall="" seq_cpu=""
    w=$WINDOW; u=$v
    [[ "$v" == *" @"* ]] && w=${v##*@} u=${v% @*}
    for th in 1 2; do
      load=$(cut -d' ' -f1-3 /proc/loadavg)
      atol=""; [ "$u" != default ] && atol=$u
      row=$(BENCH_THREADS=$th BENCH_WINDOW_MS=$w BENCH_ATOL_UNITS=$atol BENCH_INTEGRATOR=$integ \
            "$BENCH" 9000 three auto $mn $tol parts 2>/dev/null | tail -1)
      wall=$(awk '{print $(NF-9)}' <<< "$row"); cpu=$(awk '{print $(NF-8)}' <<< "$row"); steps=$(awk '{print $(NF-7)}' <<< "$row")
      [ -z "$seq_wall" ] && seq_wall=$wall seq_cpu=$cpu
      printf "%-8s %-30s %7s %8s %8s %8s %9.2f %9.2f  %s\n" $mn "$v" $th "$wall" "$cpu" "$steps" \
        "$(awk -v a="$wall" -v b="$seq_wall" 'BEGIN{print a/b}')" "$(awk -v a="$cpu" -v b="$seq_cpu" 'BEGIN{print a/b}')" "$load"
    done
  done
done
