#!/usr/bin/env bash
# Every shipped config, whatever its model kind, runs with `phasmid simulate`, has features
# that `phasmid features` reads back, and renders with `phasmid report` (issue #16's contract:
# one interface for every model). Usage: configs.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$1
SRC=$2
fail=0
n=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for cfg in "$SRC"/configs/*.toml; do
  name=$(basename "$cfg" .toml)
  n=$((n + 1))
  if ! "$PHASMID" simulate "$cfg" -q -o "$tmp/$name.h5" 2>"$tmp/err"; then
    echo "FAIL simulate $name: $(cat "$tmp/err")"; fail=1; continue
  fi
  count=$("$PHASMID" features "$tmp/$name.h5" --json | grep -c '"name"')
  if [ "$count" -lt 1 ]; then echo "FAIL features $name: no features"; fail=1; fi
  if ! "$PHASMID" report "$tmp/$name.h5" -o "$tmp/$name.html" 2>"$tmp/err" || ! grep -q "<html" "$tmp/$name.html"; then
    echo "FAIL report $name: $(cat "$tmp/err")"; fail=1
  fi
  echo "ok $name ($count features)"
done
# every kind the configs use is listed by `phasmid models`
kinds=$("$PHASMID" models --json)
for kind in mechanical_joint coupled_ctr_fti single_joint leg three_legs curve_walking cruse1980 ishigami sobol_g stuart_landau van_der_pol relay_oscillator; do
  grep -q "\"type\": \"$kind\"" <<<"$kinds" || { echo "FAIL models: $kind not listed"; fail=1; }
done
"$PHASMID" models "$SRC/configs/cruse1980_table1.toml" | grep -q "^table1_stable " || { echo "FAIL models: catalogue of cruse1980_table1"; fail=1; }
[ "$n" -ge 30 ] || { echo "FAIL: only $n configs found in $SRC/configs"; fail=1; }
exit $fail
