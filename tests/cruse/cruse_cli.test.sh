#!/usr/bin/env bash
# End-to-end: the generic verbs on Cruse configs and the SimRoach2 verb from outside the source tree (embedded configs and
# tables), and non-zero exits with a one-line reason on bad input.
set -u
PHASMID=$1
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

out=$("$PHASMID" simulate cruse1980_gait2 -o run.h5 2>&1) || { echo "simulate cruse1980 failed"; fail=1; }
grep -q "in phase: L1-R2 L2-R3" <<<"$out" || { echo "gait II pattern missing: $out"; fail=1; }
[ -f run.h5 ] && [ ! -f run.h5.tmp ] || { echo "HDF5 not committed"; fail=1; }

out=$("$PHASMID" simulate cruse1980_gait1 -o g1.h5 2>&1) || { echo "gait I failed"; fail=1; }
grep -q "lag L3->L1 1000.0 ms" <<<"$out" || { echo "gait I lag should equal the 1000 ms period: $out"; fail=1; }

"$PHASMID" simulate cruse1980_gait2 --set T9=1 2>err.txt && { echo "unknown --set accepted"; fail=1; }
[ "$(wc -l <err.txt)" -eq 1 ] && grep -q "T9" err.txt || { echo "bad message: $(cat err.txt)"; fail=1; }

printf '[model]\ntype = "cruse1980"\n[parameters]\nT1 = 7\nT3 = 1\n' >bad.toml
"$PHASMID" simulate bad.toml 2>err.txt && { echo "unknown parameter accepted"; fail=1; }
grep -q "bad.toml:5: .*'T3'" err.txt || { echo "bad message: $(cat err.txt)"; fail=1; }
printf 'model = "cruse1980"\n[cruse1980]\nT1 = 7\n' >old.toml
"$PHASMID" simulate old.toml 2>err.txt && { echo "old cruse1980 form accepted"; fail=1; }
[ "$(wc -l <err.txt)" -eq 1 ] && grep -q 'old.toml:1: .*write \[model\] with type = "cruse1980"' err.txt || { echo "bad message: $(cat err.txt)"; fail=1; }

# phasmid fit on a cruse1980 config: Ceres needs Jacobians the oscillators do not have.
"$PHASMID" fit fit_cruse1980_switch.toml --optimizer ceres -o f.h5 2>err.txt
[ $? -eq 1 ] || { echo "ceres on cruse1980 should exit 1"; fail=1; }
[ "$(wc -l <err.txt)" -eq 1 ] && grep -q "needs a gradient but the model has none" err.txt || { echo "bad message: $(cat err.txt)"; fail=1; }
"$PHASMID" fit fit_cruse1980_switch.toml --target-set nope 2>err.txt && { echo "unknown target set accepted"; fail=1; }
grep -q "no targets in set 'nope' (sets: closed_form_lag, default)" err.txt || { echo "bad message: $(cat err.txt)"; fail=1; }

out=$("$PHASMID" simroach2 check-muscles) || { echo "check-muscles failed"; fail=1; }
grep -q "51 of 60 muscles" <<<"$out" || { echo "check-muscles summary: $out"; fail=1; }

exit $fail
