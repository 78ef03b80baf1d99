#!/usr/bin/env bash
# phasmid sweep CLI contract: bad [sweep] input is one stderr line naming file:line and leaves
# no file; a stopped sweep leaves only its journal and says how to resume; --resume finishes it.
set -u
PHASMID="$1"; SRC="$2"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; pass=0
ok() { pass=$((pass+1)); }
bad() { echo "FAIL: $*"; fail=$((fail+1)); }
expect_error() {  # description, expected substring, command...
  local desc="$1" want="$2"; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  if [ $rc -eq 0 ] || ! grep -qF -- "$want" "$tmp/err" || [ "$(wc -l <"$tmp/err")" -ne 1 ]; then
    bad "$desc (rc=$rc, stderr: $(cat "$tmp/err"))"; else ok; fi
}
head='[model]
type = "mechanical_joint"
[simulation]
t_end_ms = 1500
discard_ms = 500
'
printf '%s[sweep]\n[[sweep.parameter]]\nname = "middle.fti.b_vv"\nvalues = [1, 2]\n' "$head" >"$tmp/unknown.toml"
expect_error "unknown swept parameter names file:line" "unknown.toml:8: unknown parameter 'middle.fti.b_vv'" \
  "$PHASMID" sweep "$tmp/unknown.toml" -o "$tmp/u.h5" -q
[ -e "$tmp/u.h5" ] || [ -e "$tmp/u.h5.journal" ] && bad "output left after bad input"
printf '%s[sweep]\ndesign = "lhs"\npoints = 4\n[[sweep.parameter]]\nname = "middle.fti.b_v"\nlower = 1\nupper = -3\n' "$head" >"$tmp/range.toml"
expect_error "out-of-range bound names file:line" "range.toml:12: impossible value -3" \
  "$PHASMID" sweep "$tmp/range.toml" -o "$tmp/r.h5" -q
printf '%s[sweep]\npoints = "many"\n' "$head" >"$tmp/points.toml"
expect_error "non-integer points names file:line" "points.toml:7: 'points' must be a positive integer" \
  "$PHASMID" sweep "$tmp/points.toml" -o "$tmp/p.h5" -q
expect_error "config without [sweep]" "missing [sweep] section" \
  "$PHASMID" sweep "$SRC/configs/fti_mechanical.toml" -o "$tmp/n.h5" -q

# stop after 3 points: exit 3, journal only, one line telling how to resume
good="$SRC/configs/sweep_fti_mechanics.toml"
"$PHASMID" sweep "$good" -o "$tmp/g.h5" -q --stop-after 3 -j 1 2>"$tmp/err"; rc=$?
[ $rc -eq 3 ] && grep -q -- "--resume" "$tmp/err" && [ "$(wc -l <"$tmp/err")" -eq 1 ] && ok || bad "stop-after (rc=$rc: $(cat "$tmp/err"))"
[ ! -e "$tmp/g.h5" ] && [ -e "$tmp/g.h5.journal" ] && ok || bad "stopped sweep must leave the journal and no g.h5"
expect_error "existing journal is not overwritten without --resume" "pass --resume" \
  "$PHASMID" sweep "$good" -o "$tmp/g.h5" -q
expect_error "journal of another sweep is refused" "belongs to a different sweep" \
  "$PHASMID" sweep "$good" -o "$tmp/g.h5" -q --resume --set middle.fti.b_v=13
"$PHASMID" sweep "$good" -o "$tmp/g.h5" -q --resume -j 2 && [ -e "$tmp/g.h5" ] && [ ! -e "$tmp/g.h5.journal" ] \
  && ok || bad "resume did not complete"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
