#!/usr/bin/env bash
# A fit to a recording (docs/recordings.md, "Fitting the model to a recording") recovers known
# parameters: the middle leg with rate motoneurons is run with CPG time-scale coefficients
# epsilon at 0.75 x Table A.1 (a step period of 708 ms, against the default 506 ms) and the LD
# levator drive at 0.30 nS; its steady steps are written as a Stick Insect Locomotion trial at
# 200 Hz (tests/fixtures/run_to_trial.py), starting at an arbitrary phase, in lab conventions
# (data = sign * model + offset, the FTi reversed and shifted by 200 deg). From a start 5 %
# off, `phasmid fit` must give back epsilon (PR), the drive and the FTi offset within 3 standard
# errors and 0.5 %: the data hold no noise but the 5 ms frames that time each touchdown and
# lift-off. The report draws each observable's step cycle. Usage: PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
/usr/bin/python3 -c 'import scipy, h5py' 2>/dev/null || { echo "SKIP: Debian's python3 has no scipy/h5py"; exit 0; }
source "$SRC/tests/report/chromium.sh"  # $tmp (the working directory), render NAME
sed -e 's/^thc_table = "A.17"/thc_table = "A.17"\nmotoneuron = "rate"/' -e 's/^t_end_ms = .*/t_end_ms = 20000/' \
  "$SRC/configs/middle_leg_forward.toml" >truth.toml
"$PHASMID" simulate truth.toml -q -o truth.h5 --set middle.thc.cpg.epsilon=0.001425 --set middle.ctr.cpg.epsilon=0.0009 \
  --set middle.fti.cpg.epsilon=0.001725 --set middle.ctr.cpg_lev.g_app=0.30 || { echo "FAIL truth run"; exit 1; }
# From 10.3 s: the model's own transient is over (the FTi angle near touchdown settles within
# about 8 s); the fit's model discards 9 s for the same reason.
/usr/bin/python3 "$SRC/tests/fixtures/run_to_trial.py" truth.h5 trial.mat --start-ms 10333 || { echo "FAIL trial"; exit 1; }
cat >fit.toml <<'TOML'
[model]
type = "leg"
leg = "middle"
thc_table = "A.17"
motoneuron = "rate"
[parameters]
"middle.ctr.cpg.epsilon" = 0.0009
"middle.fti.cpg.epsilon" = 0.001725
[fit]
optimizer = "ceres"
max_iterations = 15
# The cost is known to about 1e-4 of itself (the solver's tolerance moves the event times), so a
# relative change below 1e-3 is convergence; it moves the estimates by far less than their SE.
function_tolerance = 1e-3
t_end_ms = 12500
discard_ms = 9000
absolute_sigma = true
[fit.parameters]
"middle.thc.cpg.epsilon" = { nominal = 0.0015, lower = 0.0008, upper = 0.003, scale = "log" }
"middle.ctr.cpg_lev.g_app" = { nominal = 0.315, lower = 0.2, upper = 0.45 }
"thc_offset" = { nominal = -70.0, lower = -180.0, upper = 180.0, estimate = false }
"fti_offset" = { nominal = 195.0, lower = -360.0, upper = 360.0 }
[[fit.recording]]
leg = "L2"
bins = 40
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
"$PHASMID" fit fit.toml --data trial.mat -o fit.h5 -q --json >fit.json || { echo "FAIL fit (exit $?)"; exit 1; }
/usr/bin/python3 - <<'PY' || fail=1
import json
truth = {"middle.thc.cpg.epsilon": 0.001425, "middle.ctr.cpg_lev.g_app": 0.30, "fti_offset": 200.0}
r = json.load(open("fit.json"))
for p in r["parameters"]:
    t, e, se = truth[p["name"]], p["estimate"], p["standard_error"]
    ok = abs(e - t) <= 3 * se and abs(e - t) <= 0.005 * abs(t)
    print("%s %s: %.6g (truth %.6g, SE %.3g, %.2f SE)" % ("ok" if ok else "FAIL", p["name"], e, t, se, (e - t) / se))
    assert ok
PY
# An estimated noise needs absolute_sigma (the likelihood's own scale): one line, no output.
sed -e 's/^absolute_sigma = true/absolute_sigma = false/' -e 's/^offset = "fti_offset"/&\nsigma_deg = "fti_sigma"/' \
  -e 's/^\[fit.parameters\]/&\n"fti_sigma" = { nominal = 2.0, lower = 0.1, upper = 20.0, scale = "log" }/' fit.toml >noise.toml
err=$("$PHASMID" fit noise.toml --data trial.mat -o noise.h5 -q 2>&1)
want='phasmid: error: noise.toml:36: sigma_deg = "fti_sigma" estimates the noise; set absolute_sigma = true in [fit]'
if [ "$err" = "$want" ] && [ ! -e noise.h5 ]; then echo "ok: estimated noise without absolute_sigma refused"
else echo "FAIL: estimated noise without absolute_sigma: '$err'"; fail=1; fi
render fit && grep -q 'id="fig-fit-steps-0-L2.fti"' fit.dom && echo "ok report: step cycle of L2.fti" \
  || { echo "FAIL report: no step-cycle figure of L2.fti"; fail=1; }
# The caption says what the model matches: here the period and duty factor, within their noise.
grep -o 'steps) (matched); duty factor [0-9.]* vs [0-9.]* (matched)' fit.dom | head -1 | grep -q . &&
  echo "ok report: period and duty factor matched" || { echo "FAIL report: no 'matched' in the caption"; fail=1; }
exit $fail
