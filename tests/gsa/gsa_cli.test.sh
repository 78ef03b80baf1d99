#!/usr/bin/env bash
# phasmid gsa on the sweep engine (docs/gsa.md): an analysis stopped part-way (--stop-after) or
# killed with SIGKILL and then resumed with --resume writes the same /sweep and /gsa, bit for
# bit, as the uninterrupted run; --resume of a finished file repeats only the analysis; bad
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

"$PHASMID" gsa small.toml -o full.h5 -q -j 2 || bad "uninterrupted run"
"$PHASMID" gsa small.toml -o part.h5 -q -j 2 --stop-after 3000 2>err; rc=$?
[ $rc -ne 0 ] && [ ! -e part.h5 ] && [ "$(($(wc -l <part.h5.journal) - 1))" -eq 3000 ] && ok || bad "stop-after 3000 (rc=$rc: $(cat err))"
"$PHASMID" gsa small.toml -o part.h5 -q -j 1 --resume && same "stopped and resumed" full.h5 part.h5
"$PHASMID" gsa small.toml -o full.h5 --resume >out 2>err && grep -q "^y (1): 1024 of 1024 base rows used" out && ok \
  || bad "--resume of a finished file re-analyses it ($(cat err))"

# SIGKILL part-way through the sweep; the journal keeps every finished point
"$PHASMID" gsa large.toml -o large_full.h5 -q -j 1 || bad "uninterrupted large run"
"$PHASMID" gsa large.toml -o k.h5 -q -j 1 &
pid=$!
# Up to 2 min for 20 000 points: an instrumented (sanitizer) build is many times slower.
for _ in $(seq 6000); do
  [ -e k.h5.journal ] && [ "$(wc -l <k.h5.journal)" -ge 20000 ] && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.02
done
kill -9 $pid; wait $pid 2>/dev/null
kept=$(($(wc -l <k.h5.journal) - 1))
[ ! -e k.h5 ] && [ "$kept" -ge 20000 ] && [ "$kept" -lt 131072 ] && ok || bad "kill -9: $kept points journalled, k.h5 $( [ -e k.h5 ] && echo exists || echo absent)"
"$PHASMID" gsa large.toml -o k.h5 -q -j 2 --resume 2>err && same "killed and resumed" large_full.h5 k.h5 || bad "resume after kill: $(cat err)"

# errors name file:line and the key
sed 's/^features = \["y"\]/features = ["yy"]/' small.toml >feat.toml
expect_error "unknown feature" "feat.toml:.*unknown feature 'yy' (did you mean 'y'?)" "$PHASMID" gsa feat.toml -o f.h5 -q
sed 's/^method = "sobol"/method = "sobol"\ntrajectories = 4/' small.toml >keys.toml
expect_error "Morris key under sobol" "keys.toml:.*unknown key 'trajectories'" "$PHASMID" gsa keys.toml -o g.h5 -q
printf '[sweep]\ndesign = "lhs"\n' >>small.toml
expect_error "design keys are [gsa]'s" "small.toml:.*unknown key 'design'" "$PHASMID" gsa small.toml -o h.h5 -q
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
