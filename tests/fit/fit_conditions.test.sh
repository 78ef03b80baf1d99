#!/usr/bin/env bash
# Two trials fitted at once (docs/recordings.md, "Several trials"): the middle leg (rate
# motoneurons) is run twice with shared mechanics and levator drive (0.30 nS) and CPG time-scale
# coefficients epsilon of its own per trial (0.75 and 0.85 x Table A.1: step periods 708 and
# 627 ms); each run's steady steps become a Stick Insect Locomotion trial at 200 Hz
# (tests/fixtures/run_to_trial.py), in lab conventions (the FTi reversed and shifted by 200 deg).
# One `phasmid fit` with [fit.conditions.a] and [fit.conditions.b] must give back each trial's
# epsilon (PR) and the shared drive and FTi offset, from a start 5 % off, within 3 standard
# errors and 0.5 %; /fit/conditions holds each trial's values, /fit/steps each trial's step
# cycles, and the report draws both. Usage: PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
/usr/bin/python3 -c 'import scipy, h5py' 2>/dev/null || { echo "SKIP: Debian's python3 has no scipy/h5py"; exit 0; }
source "$SRC/tests/report/chromium.sh"  # $tmp (the working directory), render NAME
sed -e 's/^thc_table = "A.17"/thc_table = "A.17"\nmotoneuron = "rate"/' -e 's/^t_end_ms = .*/t_end_ms = 20000/' \
  "$SRC/configs/middle_leg_forward.toml" >truth.toml
truth() {  # NAME EPS_THC EPS_CTR EPS_FTI
  "$PHASMID" simulate truth.toml -q -o "$1.h5" --set middle.thc.cpg.epsilon="$2" --set middle.ctr.cpg.epsilon="$3" \
    --set middle.fti.cpg.epsilon="$4" --set middle.ctr.cpg_lev.g_app=0.30 || { echo "FAIL truth run $1"; exit 1; }
  /usr/bin/python3 "$SRC/tests/fixtures/run_to_trial.py" "$1.h5" "$1.mat" --start-ms 10333 || { echo "FAIL trial $1"; exit 1; }
}
truth a 0.001425 0.0009 0.001725
truth b 0.0016150 0.00102 0.0019550
cat >fit.toml <<'TOML'
[model]
type = "leg"
leg = "middle"
thc_table = "A.17"
motoneuron = "rate"
[fit]
optimizer = "ceres"
max_iterations = 15
function_tolerance = 1e-3   # the cost is known to about 1e-4 of itself (fit_recording.test.sh)
t_end_ms = 12500
discard_ms = 9000
absolute_sigma = true
[fit.parameters]
"eps_a" = { nominal = 0.0015, lower = 0.0008, upper = 0.003, scale = "log" }
"eps_b" = { nominal = 0.0017, lower = 0.0008, upper = 0.003, scale = "log" }
"middle.ctr.cpg_lev.g_app" = { nominal = 0.315, lower = 0.2, upper = 0.45 }
"fti_offset" = { nominal = 195.0, lower = -360.0, upper = 360.0 }
"thc_offset" = { nominal = -70.0, lower = -180.0, upper = 180.0, estimate = false }
[fit.conditions.a]
"middle.thc.cpg.epsilon" = "eps_a"
"middle.ctr.cpg.epsilon" = 0.0009
"middle.fti.cpg.epsilon" = 0.001725
[fit.conditions.b]
"middle.thc.cpg.epsilon" = "eps_b"
"middle.ctr.cpg.epsilon" = 0.00102
"middle.fti.cpg.epsilon" = 0.001955
[[fit.recording]]
file = "a.mat"
leg = "L2"
bins = 40
condition = "a"
[[fit.recording.observable]]
data = "L2.thc"
model = "middle.thc"
offset = "thc_offset"
[[fit.recording.observable]]
data = "L2.ctr"
model = "middle.ctr"
offset = -10.0
[[fit.recording.observable]]
data = "L2.fti"
model = "middle.fti"
sign = -1
offset = "fti_offset"
[[fit.recording]]
file = "b.mat"
leg = "L2"
bins = 40
condition = "b"
[[fit.recording.observable]]
data = "L2.thc"
model = "middle.thc"
offset = "thc_offset"
[[fit.recording.observable]]
data = "L2.ctr"
model = "middle.ctr"
offset = -10.0
[[fit.recording.observable]]
data = "L2.fti"
model = "middle.fti"
sign = -1
offset = "fti_offset"
TOML
"$PHASMID" fit fit.toml -o fit.h5 -q --json >fit.json || { echo "FAIL fit (exit $?)"; exit 1; }
/usr/bin/python3 - <<'PY' || fail=1
import json, h5py
truth = {"eps_a": 0.001425, "eps_b": 0.001615, "middle.ctr.cpg_lev.g_app": 0.30, "fti_offset": 200.0}
r = json.load(open("fit.json"))
est = {}
for p in r["parameters"]:
    t, e, se = truth[p["name"]], p["estimate"], p["standard_error"]
    est[p["name"]] = e
    ok = abs(e - t) <= 3 * se and abs(e - t) <= 0.005 * abs(t)
    print("%s %s: %.6g (truth %.6g, SE %.3g, %.2f SE)" % ("ok" if ok else "FAIL", p["name"], e, t, se, (e - t) / se))
    assert ok
with h5py.File("fit.h5") as f:
    for c, want in (("a", est["eps_a"]), ("b", est["eps_b"])):
        d = f["/fit/conditions/%s/middle.thc.cpg.epsilon" % c]
        assert abs(d[()] - want) <= 1e-12 * want and d.attrs["fit_parameter"] == "eps_" + c, (c, d[()], want)
        assert abs(f["/fit/conditions/%s/middle.fti.cpg.epsilon" % c][()] - {"a": 0.001725, "b": 0.001955}[c]) < 1e-15
    periods = []
    for i, c in ((0, "a"), (1, "b")):
        g = f["/fit/steps/%d" % i]
        assert g.attrs["condition"] == c, (i, g.attrs["condition"])
        periods.append(g.attrs["model_period_ms"])
        assert abs(g.attrs["model_period_ms"] - g.attrs["data_period_ms"]) < 2, (c, g.attrs["model_period_ms"], g.attrs["data_period_ms"])
    assert periods[0] - periods[1] > 50, periods  # the trials walk at different speeds
    print("ok /fit/conditions and /fit/steps: periods %.1f and %.1f ms" % tuple(periods))
PY
render fit && grep -q 'id="fig-fit-steps-1-L2.fti"' fit.dom && grep -q 'Trial b: step cycle of L2.fti' fit.dom &&
  echo "ok report: trial b's step cycle of L2.fti" || { echo "FAIL report: no step-cycle figure of trial b"; fail=1; }
exit $fail
