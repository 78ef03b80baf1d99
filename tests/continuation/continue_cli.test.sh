#!/usr/bin/env bash
# `phasmid continue` end to end on the test kinds: the Stuart-Landau branch in lambda ends at
# the Hopf point lambda = 0 (docs/continuation.md), the relay oscillator with flip = true reports
# `period_doubling` at alpha = 0 (its multiplier -exp(alpha T/2) through -1), the file holds the documented /continuation
# datasets, `phasmid report` draws the branch in headless Chromium without script errors, and
# config errors name file:line. Usage: continue_cli.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$1
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/sl.toml" <<'TOML'
[model]
type = "stuart_landau"
[simulation]
rtol = 1e-10
atol = 1e-10
[continuation]
parameter = "sl.lambda"
range = [0.05, -0.01]
initial_step = 0.005
max_step = 0.01
min_step = 1e-6
section_state = "sl.y"
section_level = 0.0
section_direction = "rising"
transient_ms = 1500
max_period_ms = 150
TOML
out=$("$PHASMID" continue "$tmp/sl.toml" -o "$tmp/sl.h5" -q --json) || { echo "FAIL continue: $out"; exit 1; }
echo "$out"
# The branch so far went to sl.h5.partial after each point; the complete file replaced it.
[ -e "$tmp/sl.h5.partial" ] && { echo "FAIL: sl.h5.partial left after the run"; fail=1; }
# A directory as the output is refused before any work (one line naming it).
mkdir "$tmp/dir.h5"
err=$("$PHASMID" continue "$tmp/sl.toml" -o "$tmp/dir.h5" -q 2>&1) && { echo "FAIL: directory output accepted"; fail=1; }
grep -q "dir.h5" <<<"$err" || { echo "FAIL error text: $err"; fail=1; }
# The branch ends at the Hopf point: |lambda_H| < 1e-5, period 100 ms.
/usr/bin/python3 - "$out" <<'PY' || fail=1
import json, sys
d = json.loads(sys.argv[1])
end = d["special_points"][-1]
ok = end["kind"] == "hopf" and abs(end["parameter"]) < 1e-5 and abs(end["period_ms"] - 100) < 1e-4 and d["points"] >= 5
print("ok hopf" if ok else "FAIL hopf: %s" % end)
sys.exit(0 if ok else 1)
PY
for ds in parameter period_ms stable multipliers_real multipliers_imag multipliers_abs special_points/kind \
          special_points/parameter special_points/period_ms special_points/index features/period_ms; do
  h5ls "$tmp/sl.h5/continuation/$ds" >/dev/null 2>&1 || { echo "FAIL dataset /continuation/$ds missing"; fail=1; }
done
"$PHASMID" report "$tmp/sl.h5" -o "$tmp/sl.html" || { echo "FAIL report"; fail=1; }
if [ -x /usr/bin/chromium ]; then
  # 300 s: a hang guard only (the page's 15 s are Chromium's virtual time, not the machine's).
  timeout 300 /usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage \
    --user-data-dir="$tmp/profile" --virtual-time-budget=15000 --dump-dom "file://$tmp/sl.html" >"$tmp/dom" 2>/dev/null
  [ $? -eq 124 ] && { echo "FAIL report rendering: chromium hung (still running after 300 s)"; fail=1; }
  body=$(grep -o '<body[^>]*>' "$tmp/dom" | head -1)
  for want in 'data-status="ok"' fig-continuation-period_ms fig-continuation-multipliers table-continuation-special; do
    grep -q "$want" <<<"$body" || { echo "FAIL report rendering: no $want in $body"; fail=1; }
  done
else
  echo "FAIL chromium is required (apt-get install -y chromium)"; fail=1
fi
# The relay's flip (src/scenario/kinds/relay_oscillator.cpp): period_doubling at alpha = 0 within
# 1e-7, period 2 tau ln 3 = 21.97225 ms (the JSON prints six digits).
cat >"$tmp/flip.toml" <<'TOML'
[model]
type = "relay_oscillator"
flip = true
[simulation]
rtol = 1e-11
atol = 1e-11
[continuation]
parameter = "relay.alpha"
range = [-0.02, 0.02]
initial_step = 0.005
max_step = 0.01
section_state = "relay.x"
section_level = 0.0
section_direction = "rising"
transient_ms = 300
max_period_ms = 100
tolerance = 1e-9
TOML
out=$("$PHASMID" continue "$tmp/flip.toml" -o "$tmp/flip.h5" -q --json) || { echo "FAIL continue flip: $out"; exit 1; }
/usr/bin/python3 - "$out" <<'PY' || fail=1
import json, math, sys
d = json.loads(sys.argv[1])
pd = [s for s in d["special_points"] if s["kind"] == "period_doubling"]
ok = len(pd) == 1 and abs(pd[0]["parameter"]) < 1e-7 and abs(pd[0]["period_ms"] - 20 * math.log(3)) < 1e-4
print("ok period_doubling" if ok else "FAIL period_doubling: %s" % d["special_points"])
sys.exit(0 if ok else 1)
PY
# Errors name file:line and the key.
sed 's/parameter = "sl.lambda"/parameter = "sl.lambdaa"/' "$tmp/sl.toml" >"$tmp/bad.toml"
err=$("$PHASMID" continue "$tmp/bad.toml" -o "$tmp/bad.h5" -q 2>&1) && { echo "FAIL: unknown parameter accepted"; fail=1; }
grep -q "bad.toml:7: \[continuation\] unknown parameter 'sl.lambdaa' (did you mean 'sl.lambda'?)" <<<"$err" || { echo "FAIL error text: $err"; fail=1; }
sed 's/section_direction = "rising"/section_direction = "up"/' "$tmp/sl.toml" >"$tmp/bad2.toml"
err=$("$PHASMID" continue "$tmp/bad2.toml" -o "$tmp/bad.h5" -q 2>&1) && { echo "FAIL: bad direction accepted"; fail=1; }
grep -q "bad2.toml:14: \[continuation\] section_direction must be" <<<"$err" || { echo "FAIL error text: $err"; fail=1; }
printf 'held_phases = ["front.liftoff"]\n' >>"$tmp/sl.toml"
err=$("$PHASMID" continue "$tmp/sl.toml" -o "$tmp/bad.h5" -q 2>&1) && { echo "FAIL: held phase of a leg the model lacks accepted"; fail=1; }
grep -q "sl.toml:17: \[continuation\] held_phases 'front.liftoff' is not an event of this model" <<<"$err" || { echo "FAIL error text: $err"; fail=1; }
exit $fail
