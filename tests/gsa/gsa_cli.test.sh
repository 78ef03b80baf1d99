#!/usr/bin/env bash
# phasmid gsa on the sweep engine (docs/gsa.md): an analysis stopped part-way (--stop-after) or
# killed with SIGKILL and then resumed with --resume writes the same /sweep and /gsa, bit for
# bit, as the uninterrupted run; --resume of a finished file repeats only the analysis, and is
# refused (like a journal's) when a model parameter or --set changed; a kill during the analysis
# leaves no OUT without /gsa; bad
# [gsa] sections are one-line errors naming file:line. Usage: gsa_cli.test.sh PHASMID SOURCE_DIR
set -u
PHASMID="$1"; SRC="$2"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0; pass=0
ok() { pass=$((pass+1)); }
bad() { echo "FAIL: $*"; fail=$((fail+1)); }
source "$SRC/tests/cli/expect_error.sh"
same() {  # description, file a, file b: every dataset and attribute under /sweep and /gsa
  if h5diff -q "$2" "$3" /sweep /sweep && h5diff -q "$2" "$3" /gsa /gsa; then ok; else bad "$1: $2 and $3 differ"; fi
}
# Ishigami with N = 1024 (8192 points, a fraction of a second) and N = 16384 (131072 points, seconds).
sed 's/^N = 8192/N = 1024/' "$SRC/configs/gsa_ishigami.toml" >small.toml
sed 's/^N = 8192/N = 16384/' "$SRC/configs/gsa_ishigami.toml" >large.toml

# Ishigami at N = 16, built to be unresolved: every index whose interval is wider than 0.1 (or
# that lies outside [-0.05, 1.05]) carries '*' in the table, the note names a larger N, and the
# file holds the same marks (docs/gsa.md, "Resolved indices"); at N = 1024 nothing is marked.
sed 's/^N = 8192/N = 16/; s/^second_order = true/second_order = false/' "$SRC/configs/gsa_ishigami.toml" >n16.toml
"$PHASMID" gsa n16.toml -o n16.h5 2>/dev/null >n16.out || bad "N = 16 run failed"
marked=$(grep -cE '^  x[123] .*\*' n16.out)
note=$(grep -oE 'not resolved at N = 16 .*about N = [0-9]+ would resolve them' n16.out)
named=$(echo "$note" | grep -oE 'about N = [0-9]+' | grep -oE '[0-9]+$')
[ "$marked" -ge 1 ] && [ -n "$note" ] && [ "${named:-0}" -gt 16 ] && ok || bad "N = 16: $marked rows marked, note '$note': $(cat n16.out)"
flags=$(h5dump -d /gsa/y/ST_resolved -y n16.h5 2>/dev/null | awk '/DATA \{/ { getline; print; exit }' | grep -oE '[01]' | tr -d '\n')
unmarked_st=$(awk '/^  x[123] /{ n = split($0, f, "±"); print (f[3] ~ /\*/) ? 0 : 1 }' n16.out | tr -d '\n')
[ -n "$flags" ] && [ "$flags" = "$unmarked_st" ] && ok || bad "N = 16: ST_resolved '$flags' against the table's '$unmarked_st'"
sed 's/^second_order = true/second_order = false/' small.toml >small1.toml
"$PHASMID" gsa small1.toml -o resolved.h5 2>/dev/null >resolved.out || bad "N = 1024 run failed"
! grep -q '\*' resolved.out && [ "$(h5dump -a /gsa/y/n_unresolved resolved.h5 | grep -oE '\(0\): [0-9]+')" = "(0): 0" ] && ok \
  || bad "N = 1024 marks indices: $(cat resolved.out)"
rm -f n16.h5 resolved.h5

"$PHASMID" gsa small.toml -o full.h5 -q -j 2 || bad "uninterrupted run"
"$PHASMID" gsa small.toml -o part.h5 -q -j 2 --stop-after 3000 2>err; rc=$?
[ $rc -ne 0 ] && [ ! -e part.h5 ] && [ "$(($(wc -l <part.h5.journal) - 1))" -eq 3000 ] && ok || bad "stop-after 3000 (rc=$rc: $(cat err))"
"$PHASMID" gsa small.toml -o part.h5 -q -j 1 --resume && same "stopped and resumed" full.h5 part.h5
"$PHASMID" gsa small.toml -o full.h5 --resume >out 2>err && grep -q "^y (1): 1024 of 1024 base rows used" out && ok \
  || bad "--resume of a finished file re-analyses it ($(cat err))"

# --resume compares everything that determines the result (docs/gsa.md, docs/sweep.md "Interrupting
# and resuming"): a changed model parameter or --set is refused for a finished file and for a
# journal, naming it, and nothing is written; another -j is no change.
sed 's/^a = 7.0/a = 0.0/' small.toml >a0.toml
before=$(h5dump -a /config full.h5 | md5sum)
expect_error "finished file, a changed" "the config differs from the one full.h5 was made with (model parameter a: 7 in full.h5, 0 now)" \
  "$PHASMID" gsa a0.toml -o full.h5 --resume -q
expect_error "finished file, --set b=0.5" "(model parameter b: 0.1 in full.h5, 0.5 now)" "$PHASMID" gsa small.toml -o full.h5 --resume -q --set b=0.5
[ "$(h5dump -a /config full.h5 | md5sum)" = "$before" ] && [ ! -e full.h5.tmp ] && ok || bad "a refused resume touched full.h5"
"$PHASMID" gsa small.toml -o j.h5 -q -j 2 --stop-after 500 2>/dev/null
expect_error "journal, a changed" "journal belongs to a different sweep: the config differs from the one it was started with (model parameter a: 7 in the journal, 0 now)" \
  "$PHASMID" gsa a0.toml -o j.h5 --resume -q
expect_error "journal, --set b=0.5" "(model parameter b: 0.1 in the journal, 0.5 now)" "$PHASMID" gsa small.toml -o j.h5 --resume -q --set b=0.5
[ ! -e j.h5 ] && [ "$(($(wc -l <j.h5.journal) - 1))" -eq 500 ] && ok || bad "a refused resume changed the journal or wrote j.h5"
"$PHASMID" gsa small.toml -o j.h5 -q -j 1 --resume && same "resumed with another -j" full.h5 j.h5
sed 's/^bootstrap = 200/bootstrap = 100/' small.toml >boot.toml
"$PHASMID" gsa boot.toml -o j.h5 -q --resume && ok || bad "another [gsa] bootstrap count does not re-analyse a finished file"

# SIGKILL part-way through the sweep; the journal keeps every finished point
"$PHASMID" gsa large.toml -o large_full.h5 -q -j 1 || bad "uninterrupted large run"
"$PHASMID" gsa large.toml -o k.h5 -q -j 1 &
pid=$!
# Killed once 20 000 points are journalled, 111 072 of the same work each still to come. The
# 300 s only catch a hung run (an instrumented build is many times slower): no speed limit.
end=$((SECONDS + 300))
until [ -e k.h5.journal ] && [ "$(wc -l <k.h5.journal)" -gt 20000 ]; do
  kill -0 $pid 2>/dev/null || { bad "kill -9: the run ended before 20 000 points were journalled"; break; }
  [ $SECONDS -lt $end ] || { bad "kill -9: hung: fewer than 20 000 points journalled after 300 s"; break; }
  sleep 0.02
done
kill -9 $pid; wait $pid 2>/dev/null
kept=$(($(wc -l <k.h5.journal) - 1))
[ ! -e k.h5 ] && [ "$kept" -ge 20000 ] && [ "$kept" -lt 131072 ] && ok || bad "kill -9: $kept points journalled, k.h5 $( [ -e k.h5 ] && echo exists || echo absent)"
"$PHASMID" gsa large.toml -o k.h5 -q -j 2 --resume 2>err && same "killed and resumed" large_full.h5 k.h5 || bad "resume after kill: $(cat err)"

# Killed during the analysis: the sweep is complete in k2.h5.sweep and the journal, and k2.h5 does not
# exist until it holds /gsa. Killed as soon as k2.h5.sweep appears; had the run already ended, k2.h5
# must be complete. Either way --resume gives the uninterrupted file.
"$PHASMID" gsa large.toml -o k2.h5 -q -j 2 &
pid=$!
until [ -e k2.h5.sweep ] || ! kill -0 $pid 2>/dev/null; do sleep 0.01; done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
if [ -e k2.h5 ]; then
  h5dump -H -g /gsa k2.h5 >/dev/null 2>&1 && [ ! -e k2.h5.journal ] && ok || bad "k2.h5 without /gsa, or with its journal"
else
  [ -e k2.h5.journal ] && ok || bad "killed in the analysis: no k2.h5 and no journal"
  expect_error "report of the unfinished analysis" "k2.h5: no such file" "$PHASMID" report k2.h5
fi
"$PHASMID" gsa large.toml -o k2.h5 -q --resume 2>err && same "killed in the analysis and resumed" large_full.h5 k2.h5 || bad "resume after a kill in the analysis: $(cat err)"
[ ! -e k2.h5.sweep ] && [ ! -e k2.h5.journal ] && ok || bad "k2.h5.sweep or the journal left after the resume"

# errors name file:line and the key
sed 's/^features = \["y"\]/features = ["yy"]/' small.toml >feat.toml
expect_error "unknown feature" "feat.toml:.*unknown feature 'yy' (did you mean 'y'?)" "$PHASMID" gsa feat.toml -o f.h5 -q
sed 's/^method = "sobol"/method = "sobol"\ntrajectories = 4/' small.toml >keys.toml
expect_error "Morris key under sobol" "keys.toml:.*unknown key 'trajectories'" "$PHASMID" gsa keys.toml -o g.h5 -q
printf '[sweep]\ndesign = "lhs"\n' >>small.toml
expect_error "design keys are [gsa]'s" "small.toml:.*unknown key 'design'" "$PHASMID" gsa small.toml -o h.h5 -q
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
