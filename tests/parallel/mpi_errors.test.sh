#!/usr/bin/env bash
# One line under MPI (docs/cluster.md "Messages and exit status"): bad configs, options and
# resumes of sweep, gsa and fit (and the verbs that do not run under MPI) under
# `mpirun -np 3 --oversubscribe` each print exactly one phasmid line on stderr plus only the
# lines Open MPI's mpirun itself prints when a rank exits non-zero (openmpi_lines below, the
# list docs/cluster.md gives), exit non-zero, and leave no output file.
# Usage: mpi_errors.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
source "$SRC/tests/parallel/mpi_env.sh"   # skips without MPI; runs in a fresh temporary directory

# What mpirun (Open MPI 4.1) prints when a rank exits non-zero; everything else on stderr is phasmid's.
openmpi_lines='^-+$|^Primary job +terminated normally, but [0-9]+ process(es)? returned$|^a non-zero exit code\. Per user-direction, the job has been aborted\.$|^mpirun detected that one or more processes exited with non-zero status, thus causing$|^the job to be terminated\. The first process to do so was:$|^$|^ +Process name: \[\[[0-9]+,[0-9]+\],[0-9]+\]$|^ +Exit code: +[0-9]+$'

cat "$SRC/tests/fixtures/fti_mechanics_short.toml" "$SRC/tests/fixtures/b_v_grid.toml" >sweep.toml
sed 's/^N = 8192/N = 64/' "$SRC/configs/gsa_ishigami.toml" >gsa.toml
sed -e "s#\.\./datasets/synthetic/#$SRC/datasets/synthetic/#g" "$SRC/configs/fit_fti_kinematic_synthetic.toml" >fit.toml
base=$PWD

# mcase NAME EXPECTED(grep -E on phasmid's line) SETUP ARGS...: SETUP runs in a fresh directory
# (with sweep.toml, gsa.toml and fit.toml), then `mpirun -np 3 phasmid ARGS` there.
mcase() {
  local name=$1 want=$2 setup=$3; shift 3
  local d="$base/case_$name"; mkdir -p "$d"; cp "$base"/*.toml "$d"
  (cd "$d" && eval "$setup") >"$d.setup" 2>&1 || { bad "$name: setup failed: $(head -c 300 "$d.setup")"; return; }
  local before; before=$(cd "$d" && find . | sort)
  (cd "$d" && timeout -k 10 300 mpirun --oversubscribe -np 3 "$PHASMID" "$@") >"$d.out" 2>"$d.err" </dev/null
  local rc=$?
  local after; after=$(cd "$d" && find . | sort)
  local ours; ours=$(grep -vE "$openmpi_lines" "$d.err")
  local why=""
  [ $rc -eq 0 ] && why="exit 0"
  [ $rc -eq 124 ] && why="hung"
  [ "$(printf '%s\n' "$ours" | grep -c .)" -eq 1 ] || why="$why; not one line besides Open MPI's"
  printf '%s\n' "$ours" | grep -qE -- "^phasmid: (internal )?error: .*($want)" || why="$why; no line matching '$want'"
  [ "$before" != "$after" ] && why="$why; files left: $(comm -13 <(echo "$before") <(echo "$after") | tr '\n' ' ')"
  if [ -n "$why" ]; then bad "$name:${why#;} -- stderr: $(head -c 600 "$d.err")"; else ok; fi
}

# sweep: config, --set, ranges, options and files
mcase s-unknown-key "c.toml:[0-9]+: .*unknown key 'rtoll'" "sed 's/^rtol = 1e-6/rtoll = 1e-6/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-rtol-negative "c.toml:[0-9]+: .*rtol" "sed 's/^rtol = 1e-6/rtol = -1/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-t-end-zero "c.toml:[0-9]+: .*t_end_ms" "sed 's/^t_end_ms = 300/t_end_ms = 0/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-t-end-text "c.toml:[0-9]+: .*t_end_ms" "sed 's/^t_end_ms = 300/t_end_ms = \"long\"/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-unknown-section "unknown section \[sweeps\]" "printf '[sweeps]\nx = 1\n' >>sweep.toml" sweep sweep.toml -o out.h5
mcase s-unknown-kind "c.toml:[0-9]+: .*nope" "sed 's/^type = .*/type = \"nope\"/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-malformed "c.toml:[0-9]+: malformed config" "cp sweep.toml c.toml; echo 'x = = 1' >>c.toml" sweep c.toml -o out.h5
mcase s-missing-config "missing.toml" ":" sweep missing.toml -o out.h5
mcase s-unknown-parameter "middle.fti.nope" "printf '[parameters]\n\"middle.fti.nope\" = 1\n' >>sweep.toml" sweep sweep.toml -o out.h5
mcase s-parameter-range "middle.fti.b_v" "printf '[parameters]\n\"middle.fti.b_v\" = -5\n' >>sweep.toml" sweep sweep.toml -o out.h5
mcase s-set-unknown "nope" ":" sweep sweep.toml -o out.h5 --set nope=1
mcase s-set-malformed "--set" ":" sweep sweep.toml -o out.h5 --set middle.fti.b_v
mcase s-set-text "middle.fti.b_v|abc" ":" sweep sweep.toml -o out.h5 --set middle.fti.b_v=abc
mcase s-values-empty "c.toml:[0-9]+: " "sed 's/^values = .*/values = []/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-sweep-unknown-parameter "c.toml:[0-9]+: .*middle.fti.nope" "sed 's/^name = .*/name = \"middle.fti.nope\"/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-range-reversed "c.toml:[0-9]+: " "sed 's/^values = .*/lower = 20.0\nupper = 10.0\nsteps = 3/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-design-unknown "c.toml:[0-9]+: design must be" "sed 's/^design = .*/design = \"nope\"/' sweep.toml >c.toml" sweep c.toml -o out.h5
mcase s-threads-huge "not in range 0 to 256" ":" sweep sweep.toml -o out.h5 -j 100000
mcase s-shard-bad "--shard" ":" sweep sweep.toml -o out.h5 --shard 5/2
mcase s-unknown-option "bogus" ":" sweep sweep.toml -o out.h5 --bogus
mcase s-output-directory "out.h5.*directory" "mkdir out.h5" sweep sweep.toml -o out.h5
mcase s-output-is-config "sweep.toml" ":" sweep sweep.toml -o sweep.toml
mcase s-journal-exists "journal of an unfinished sweep" "$PHASMID sweep sweep.toml -o out.h5 -q -j 1 --stop-after 1; [ -s out.h5.journal ]" sweep sweep.toml -o out.h5
mcase s-journal-changed "journal belongs to a different sweep: .*simulation.rtol" \
  "$PHASMID sweep sweep.toml -o out.h5 -q -j 1 --stop-after 1; sed -i 's/^rtol = 1e-6/rtol = 1e-7/' sweep.toml" sweep sweep.toml -o out.h5 --resume
mcase s-file-changed "the config differs from the one out.h5 was made with \(simulation.rtol" \
  "$PHASMID sweep sweep.toml -o out.h5 -q -j 1; sed -i 's/^rtol = 1e-6/rtol = 1e-7/' sweep.toml" sweep sweep.toml -o out.h5 --resume
# gsa
mcase g-unknown-feature "c.toml:[0-9]+: .*unknown feature 'yy'" "sed 's/^features = .*/features = [\"yy\"]/' gsa.toml >c.toml" gsa c.toml -o out.h5
mcase g-n-zero "c.toml:[0-9]+: .*N" "sed 's/^N = 64/N = 0/' gsa.toml >c.toml" gsa c.toml -o out.h5
mcase g-method "c.toml:[0-9]+: .*method" "sed 's/^method = .*/method = \"nope\"/' gsa.toml >c.toml" gsa c.toml -o out.h5
mcase g-morris-key "c.toml:[0-9]+: .*unknown key 'trajectories'" "sed 's/^method = .*/method = \"sobol\"\ntrajectories = 4/' gsa.toml >c.toml" gsa c.toml -o out.h5
mcase g-no-ranges "sweep" "awk '/^\[\[sweep.parameter\]\]/{skip=4} skip{skip--; next} 1' gsa.toml >c.toml" gsa c.toml -o out.h5
mcase g-set-text "b|text" ":" gsa gsa.toml -o out.h5 --set b=text
mcase g-file-changed "the config differs from the one out.h5 was made with \(model parameter a: 7 in out.h5, 0 now\)" \
  "$PHASMID gsa gsa.toml -o out.h5 -q; sed -i 's/^a = 7.0/a = 0.0/' gsa.toml" gsa gsa.toml -o out.h5 --resume
mcase g-file-set "\(model parameter b: 0.1 in out.h5, 0.5 now\)" "$PHASMID gsa gsa.toml -o out.h5 -q" gsa gsa.toml -o out.h5 --resume --set b=0.5
# fit
mcase f-missing-data "nowhere.csv" "sed 's#^file = .*#file = \"nowhere.csv\"#' fit.toml >c.toml" fit c.toml -o out.h5
mcase f-unknown-key "c.toml:[0-9]+: .*unknown key 'bogus'" "sed 's/^optimizer = .*/optimizer = \"ceres\"\nbogus = 1/' fit.toml >c.toml" fit c.toml -o out.h5
mcase f-multistart-text "multistart" ":" fit fit.toml -o out.h5 --multistart many
mcase f-profile-unknown "profile: 'nope' is not an estimated parameter" ":" fit fit.toml -o out.h5 --profile nope
mcase f-set-unknown "nope" ":" fit fit.toml -o out.h5 --set nope=1
# verbs that run in one process
mcase continue-under-mpi "phasmid continue runs in one process" ":" continue "$SRC/configs/continue_single_joint_vhh.toml" -o out.h5
mcase simulate-under-mpi "phasmid simulate runs in one process" ":" simulate sweep.toml -o out.h5
# A failure on a worker rank alone (its environment differs): rank 0 prints that rank's line.
awk '/^\[gsa\]/ { exit } 1' gsa.toml >lhs_small.toml
printf '[sweep]\ndesign = "lhs"\npoints = 100\n' >>lhs_small.toml
mpirun --oversubscribe -np 2 "$PHASMID" sweep lhs_small.toml -o w.h5 : -np 1 -x OMP_NUM_THREADS=1000 "$PHASMID" sweep lhs_small.toml -o w.h5 \
  >w.out 2>w.err </dev/null; rc=$?
ours=$(grep -vE "$openmpi_lines" w.err)
[ $rc -ne 0 ] && [ "$ours" = "phasmid (rank 2): error: OMP_NUM_THREADS 1000: at most 256 worker threads per process" ] && [ ! -e w.h5 ] &&
  [ ! -e w.h5.journal ] && ok || bad "a worker's own failure: rc=$rc, stderr: $(head -c 600 w.err)"

# Ctrl-C (SIGINT to mpirun) during a gsa and a sweep, once 2000 points are journalled: one line
# from rank 0 saying how to resume (besides Open MPI's), the journal kept, no OUT; --resume (in one
# process: the journal is the same with and without MPI) then gives the uninterrupted file. The
# 300 s only catch a hang.
# ctrl_c VERB CONFIG POINTS WHAT GROUPS...
ctrl_c() {
  local verb=$1 cfg=$2 points=$3 what=$4; shift 4
  "$PHASMID" "$verb" "$cfg" -o full_$verb.h5 -q -j 2 || bad "single-process $verb"
  mpirun --oversubscribe -np 3 "$PHASMID" "$verb" "$cfg" -o c.h5 -q >c.out 2>c.err </dev/null &
  local launcher=$! end=$((SECONDS + 300))
  until [ -e c.h5.journal ] && [ "$(wc -l <c.h5.journal)" -gt 2000 ]; do
    kill -0 $launcher 2>/dev/null && [ $SECONDS -lt $end ] || break
    sleep 0.02
  done
  kill -INT $launcher; wait $launcher; local rc=$?
  # On SIGINT, mpirun's event library may also warn about a descriptor it closed while
  # tearing the job down ("[warn] Epoll MOD(1) on fd N failed ..."): Open MPI's line, not ours.
  local ours; ours=$(grep -vE "$openmpi_lines|^\[warn\] Epoll [A-Z]+\([0-9]+\) on fd [0-9]+ failed" c.err)
  [ $rc -ne 0 ] && [ "$(printf '%s\n' "$ours" | grep -c .)" -eq 1 ] && [ ! -e c.h5 ] && [ -s c.h5.journal ] &&
    printf '%s\n' "$ours" | grep -qE "^phasmid $verb: interrupted with [0-9]+ of $points $what done \(kept in c.h5.journal\); continue with: mpirun \.\.\. phasmid $verb $cfg -o c.h5 --resume$" \
    && ok || bad "Ctrl-C during $verb: rc=$rc, stderr: $(head -c 600 c.err)"
  "$PHASMID" "$verb" "$cfg" -o c.h5 -q -j 2 --resume >/dev/null || bad "--resume after Ctrl-C during $verb"
  local g
  for g in "$@"; do h5diff -q full_$verb.h5 c.h5 "$g" "$g" && ok || bad "--resume after Ctrl-C during $verb: $g differs"; done
  [ ! -e c.h5.journal ] && ok || bad "journal left after the resumed $verb"
  rm -f c.h5
}
sed 's/^N = 64/N = 8192/' gsa.toml >large.toml
ctrl_c gsa large.toml 65536 "design points" /sweep /gsa
awk '/^\[gsa\]/ { exit } 1' gsa.toml >lhs.toml
printf '[sweep]\ndesign = "lhs"\npoints = 50000\n' >>lhs.toml
ctrl_c sweep lhs.toml 50000 points /sweep
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
