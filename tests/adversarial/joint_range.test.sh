#!/usr/bin/env bash
# A run whose joint angle leaves [-180, 180] deg is not a result (docs/model.md, "Admissible
# ranges"): with b_v = 0.01 g/s the prescribed FTi mechanics swing to -3353 deg by 1000 ms, so
# simulate exits 1 with one line and a sweep records that point as failed with the reason
# while the admissible point (b_v = 12.5 g/s, Table A.14) is ok.
# Usage: joint_range.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
base='[model]\ntype = "mechanical_joint"\n[simulation]\nt_end_ms = 1000\n'
printf "$base"'[parameters]\n"middle.fti.b_v" = 0.01\n' >"$tmp/sim.toml"
"$PHASMID" simulate "$tmp/sim.toml" -o "$tmp/s.h5" -q 2>"$tmp/err"; rc=$?
[ $rc -eq 1 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "joint middle.fti left its admissible range \[-180, 180\] deg at t = 82 ms" "$tmp/err" \
  && [ ! -e "$tmp/s.h5" ] || { echo "FAIL: simulate rc=$rc: $(cat "$tmp/err")"; fail=1; }
printf "$base"'[sweep]\ndesign = "grid"\n[[sweep.parameter]]\nname = "middle.fti.b_v"\nvalues = [0.01, 12.5]\n' >"$tmp/sweep.toml"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$tmp/w.h5" -q -j 1 || { echo "FAIL: sweep"; fail=1; }
status=$(h5dump -d /sweep/status "$tmp/w.h5")
grep -q '(0): "joint middle.fti left its admissible range \[-180, 180\] deg at t = 1000 ms' <<<"$status" \
  && grep -q '(1): "ok"' <<<"$status" || { echo "FAIL: sweep status: $status"; fail=1; }
[ $fail -eq 0 ] && echo "joint range: ok"
exit $fail
