#!/usr/bin/env bash
# phasmid fit from the command line: the issue-5 command on the synthetic recording, and bad
# input (malformed CSV/TSV, unknown optimizer) giving exit != 0, one line naming file:line,
# and no output file left behind.
set -u
PHASMID="$1"; SRC="$2"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; pass=0
source "$SRC/tests/cli/expect_error.sh"
DATA="$SRC/datasets/synthetic/fti_kinematics_synthetic.csv"
PARAMS="$SRC/datasets/synthetic/fti_kinematics_params.tsv"
if "$PHASMID" fit "$SRC/configs/fti_mechanical.toml" --data "$DATA" --parameters "$PARAMS" -o "$tmp/ok.h5" -q \
   && [ -s "$tmp/ok.h5" ]; then pass=$((pass+1)); else echo "FAIL: fit of the synthetic recording"; fail=$((fail+1)); fi
printf 'time_ms,middle.fti\n0,45\n5,46,1\n' >"$tmp/bad.csv"
expect_error "malformed CSV names file:line" "bad.csv:3" \
  "$PHASMID" fit "$SRC/configs/fti_mechanical.toml" --data "$tmp/bad.csv" --parameters "$PARAMS" -o "$tmp/a.h5" -q
[ -e "$tmp/a.h5" ] || [ -e "$tmp/a.h5.tmp" ] && { echo "FAIL: output left behind"; fail=$((fail+1)); }
printf 'parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\nmiddle.fti.b_v\tlog\t0\t50\t12.5\t1\n' >"$tmp/bad.tsv"
expect_error "malformed TSV names file:line" "bad.tsv:2" \
  "$PHASMID" fit "$SRC/configs/fti_mechanical.toml" --data "$DATA" --parameters "$tmp/bad.tsv" -o "$tmp/b.h5" -q
printf 'parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\nmiddle.fti.bv\tlin\t1\t50\t12.5\t1\n' >"$tmp/unk.tsv"
expect_error "unknown parameter named" "unknown parameter 'middle.fti.bv'" \
  "$PHASMID" fit "$SRC/configs/fti_mechanical.toml" --data "$DATA" --parameters "$tmp/unk.tsv" -o "$tmp/c.h5" -q
expect_error "unknown optimizer" "unknown optimizer 'nlopt:FOO' (expected one of ceres, nlopt:BOBYQA" \
  "$PHASMID" fit "$SRC/configs/fti_mechanical.toml" --data "$DATA" --parameters "$PARAMS" --optimizer nlopt:FOO -o "$tmp/d.h5" -q
expect_error "no targets" "no targets" "$PHASMID" fit "$SRC/configs/fti_mechanical.toml" --parameters "$PARAMS" -o "$tmp/e.h5" -q
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
