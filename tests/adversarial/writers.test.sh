#!/usr/bin/env bash
# Two writers on one output (docs/reliability.md, "Two writers"; issue #42): for simulate,
# sweep, gsa, gsa --resume (of a copy of a finished file) and continue, WRITERS_RUNS pairs
# (default 30) of two processes started together on one -o. In every pair, a process that
# exits 0 leaves the output an uncontended run writes (every dataset and every attribute but
# the run times, h5diff), and the other is either refused (exit 1..127, exactly one
# stderr line "output ... is being written by another phasmid process ...") or, having started
# after the first finished, also exits 0 with the same output. Nothing but OUT is left (no
# OUT.tmp, journal or .partial). Also: a `gsa --resume` while a plain `gsa` is held stopped
# (SIGSTOP) in its analysis step is refused, and the first then finishes correctly.
# Nothing here depends on speed: the pair waits on one fifo, and both outcomes are accepted.
# Usage: writers.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
RUNS=${WRITERS_RUNS:-30}
HANG_SECONDS=${HANG_SECONDS:-300}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0; pass=0
ok() { pass=$((pass+1)); }
bad() { echo "FAIL: $*"; fail=$((fail+1)); }
command -v h5diff >/dev/null || { echo "SKIP: h5diff missing (apt-get install hdf5-tools)"; exit 0; }

# Tiny jobs: short runs, few points.
sed 's/^t_end_ms = .*/t_end_ms = 300/' "$SRC/configs/fti_mechanical.toml" >sim.toml
cp sim.toml sweep.toml
printf '[sweep]\ndesign = "grid"\n[[sweep.parameter]]\nname = "middle.fti.b_v"\nvalues = [11.0, 12.0, 13.0, 14.0]\n' >>sweep.toml
sed 's/^N = 8192/N = 256/; s/^bootstrap = 200/bootstrap = 50/' "$SRC/configs/gsa_ishigami.toml" >gsa.toml
cat >cont.toml <<'TOML'
[model]
type = "stuart_landau"
[simulation]
rtol = 1e-8
atol = 1e-8
[continuation]
parameter = "sl.lambda"
range = [0.05, 0.02]
initial_step = 0.01
max_step = 0.01
min_step = 1e-6
section_state = "sl.y"
section_level = 0.0
section_direction = "rising"
transient_ms = 300
max_period_ms = 150
TOML

declare -A ARGS=(
  [simulate]="simulate sim.toml -q"
  [sweep]="sweep sweep.toml -q -j 1"
  [gsa]="gsa gsa.toml -q -j 1"
  [gsa_resume]="gsa gsa.toml -q -j 1 --resume"
  [continue]="continue cont.toml -q"
)

# same REF OUT: the same objects, and h5diff (exact) finds no difference but in the attributes
# that are times: the root's `created` and the run times (`cpu_seconds`, `wall_seconds` of
# /trajectory, `seconds` of /continuation). `command` is the same text in both runs.
timing='(created|cpu_seconds|wall_seconds|seconds)'
same() {
  [ "$(h5ls -r "$1" 2>&1 | sort)" = "$(h5ls -r "$2" 2>&1 | sort)" ] || return 1
  ! h5diff "$1" "$2" 2>&1 | grep -vE "^(attribute: <$timing of <[^>]*>> and <$timing of <[^>]*>>|[0-9]+ differences? found)\$" | grep -q .
}

# Reference outputs, uncontended, in ref/ with the same relative paths and arguments.
mkdir -p ref
for job in simulate sweep gsa gsa_resume continue; do
  [ "$job" = gsa_resume ] && cp ref/gsa.h5 ref/out.h5  # a finished file, analysed again
  (cd ref && cp ../*.toml . && "$PHASMID" ${ARGS[$job]} -o out.h5 >/dev/null 2>err.$job) || bad "$job: uncontended run failed: $(cat ref/err.$job)"
  mv ref/out.h5 ref/$job.h5 2>/dev/null
done

# pair JOB RUN: two processes on one output, released together by one write to a fifo.
pair() {
  local job=$1 run=$2 d="$tmp/run" i
  rm -rf "$d"; mkdir -p "$d"; cp ./*.toml "$d/"
  [ "$job" = gsa_resume ] && cp ref/gsa.h5 "$d/out.h5"
  mkfifo "$d/go"
  exec 3<>"$d/go"  # held open read-write: the two readers' opens do not block
  for i in 1 2; do
    (exec 3>&-; cd "$d"; read -r _ <go; exec timeout -k 10 "$HANG_SECONDS" "$PHASMID" ${ARGS[$job]} -o out.h5 >/dev/null 2>err.$i) &
    pids[$i]=$!
  done
  printf '\n\n' >&3
  wait "${pids[1]}"; rc[1]=$?
  wait "${pids[2]}"; rc[2]=$?
  exec 3>&-
  rm -f "$d/go"
  local n_ok=0 why=""
  for i in 1 2; do
    if [ "${rc[$i]}" -eq 0 ]; then n_ok=$((n_ok+1))
    elif [ "${rc[$i]}" -ge 128 ] || [ "${rc[$i]}" -eq 124 ]; then why="$why; process $i: exit ${rc[$i]} (signal or hung)"
    elif [ "$(wc -l <"$d/err.$i")" -ne 1 ] || ! grep -q "is being written by another phasmid process" "$d/err.$i"; then
      why="$why; process $i: exit ${rc[$i]}, stderr: $(head -c 300 "$d/err.$i")"
    fi
  done
  [ $n_ok -ge 1 ] || why="$why; no process succeeded"
  if [ $n_ok -ge 1 ] && ! same "ref/$job.h5" "$d/out.h5"; then
    why="$why; the output differs from the uncontended run's"
  fi
  local left; left=$(cd "$d" && ls -A | grep -vE '^(out\.h5|err\.[12]|.*\.toml)$' | tr '\n' ' ')
  [ -z "$left" ] || why="$why; files left: $left"
  if [ -n "$why" ]; then bad "$job run $run:${why#;}"; else ok; fi
  [ $n_ok -eq 2 ] && both[$job]=$((${both[$job]:-0} + 1)) || refused[$job]=$((${refused[$job]:-0} + 1))
}

declare -A both refused
for job in simulate sweep gsa gsa_resume continue; do
  for ((run = 1; run <= RUNS; run++)); do pair "$job" "$run"; done
  echo "$job: $RUNS pairs: ${refused[$job]:-0} with one refused, ${both[$job]:-0} with both exit 0 (one after the other)"
done

# A --resume while a plain gsa is in its analysis step (held there by SIGSTOP): refused, and the
# held run then finishes with the uncontended output. The sign of the analysis step: the
# complete sweep's file OUT.sweep exists (written before the analysis; OUT comes after it).
# N = 16384: 131072 points, then an analysis (bootstrap and convergence subsets) of many polls.
sed 's/^N = 8192/N = 16384/' "$SRC/configs/gsa_ishigami.toml" >big.toml
rm -rf held; mkdir -p held ref/held
"$PHASMID" gsa big.toml -o held/out.h5 -q -j 1 && mv held/out.h5 ref/held/out.h5 || bad "held: uncontended run failed"
"$PHASMID" gsa big.toml -o held/out.h5 -q -j 1 2>held/err.1 & pid=$!
end=$((SECONDS + HANG_SECONDS)); caught=0
while kill -0 $pid 2>/dev/null && [ $SECONDS -lt $end ]; do
  if [ -e held/out.h5.sweep ]; then kill -STOP $pid; caught=1; break; fi
  sleep 0.01
done
if [ $caught -eq 1 ]; then
  "$PHASMID" gsa big.toml -o held/out.h5 -q -j 1 --resume 2>held/err.2; rc=$?
  [ $rc -ne 0 ] && [ $rc -lt 128 ] && [ "$(wc -l <held/err.2)" -eq 1 ] && grep -q "being written by another phasmid process" held/err.2 \
    && ok || bad "held: --resume during the analysis step: exit $rc: $(cat held/err.2)"
  kill -CONT $pid
  wait $pid && ok || bad "held: the first gsa failed after the refusal: $(cat held/err.1)"
  same ref/held/out.h5 held/out.h5 && ok || bad "held: the first gsa's output differs from the uncontended run's"
  [ -z "$(ls -A held | grep -vE '^(out\.h5|err\.[12])$')" ] && ok || bad "held: files left: $(ls -A held)"
else
  wait $pid
  echo "NOTE: held: the gsa finished before its analysis step was seen (not checked this time)"
fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
