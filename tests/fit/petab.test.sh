#!/usr/bin/env bash
# PEtab tables of a recording fit (docs/recordings.md, "PEtab tables") round-trip: two
# synthetic trials in the database's layout (tests/fixtures/locomotion_trial.py), fitted as two
# conditions with per-bin, fixed and estimated noises, fixed and estimated offsets and a scale,
# are written by `phasmid petab`; a config that reads the tables back ([fit.petab] and the
# parameter table) gives the same fit, residual for residual and bit for bit, and writes the
# same tables again. Malformed tables are refused in one line, leaving no output.
# Usage: PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
/usr/bin/python3 -c 'import scipy, h5py' 2>/dev/null || { echo "SKIP: Debian's python3 has no scipy/h5py"; exit 0; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT; cd "$tmp"
fail=0
trial() { /usr/bin/python3 "$SRC/tests/fixtures/locomotion_trial.py" "$@" || { echo "FAIL trial $1"; exit 1; }; }
trial a.mat --periods 170,180,165 --noise 2 --seed 3
trial b.mat --periods 150,155 --noise 1 --seed 4
model='[model]
type = "leg"
leg = "middle"
thc_table = "A.17"
motoneuron = "rate"'
fit='[fit]
optimizer = "ceres"
max_iterations = 2
t_end_ms = 4200
discard_ms = 1500
absolute_sigma = true'
cat >fit.toml <<TOML
$model
$fit
[fit.parameters]
"eps_a" = { nominal = 0.0019, lower = 0.001, upper = 0.004, scale = "log" }
"eps_b" = { nominal = 0.0021, lower = 0.001, upper = 0.004, scale = "log" }
"middle.ctr.cpg_lev.g_app" = { nominal = 0.34, lower = 0.2, upper = 0.5 }
"fti_offset" = { nominal = 200.0, lower = -360.0, upper = 360.0 }
"fti_sigma" = { nominal = 5.0, lower = 0.5, upper = 50.0, scale = "log" }
"ctr_scale" = { nominal = 0.8, lower = 0.2, upper = 2.0 }
[fit.conditions.a]
"middle.thc.cpg.epsilon" = "eps_a"
[fit.conditions.b]
"middle.thc.cpg.epsilon" = "eps_b"
"middle.fti.cpg.epsilon" = 0.0025
[[fit.recording]]
file = "a.mat"
leg = "L2"
bins = 20
condition = "a"
period_sigma_ms = 30.0
[[fit.recording.observable]]
data = "L2.thc"
model = "middle.thc"
offset = -60.0
sigma_deg = 4.0
[[fit.recording.observable]]
data = "L2.ctr"
model = "middle.ctr"
scale = "ctr_scale"
[[fit.recording.observable]]
data = "L2.fti"
model = "middle.fti"
sign = -1
offset = "fti_offset"
sigma_deg = "fti_sigma"
[[fit.recording]]
file = "b.mat"
leg = "L2"
bins = 20
condition = "b"
[[fit.recording.observable]]
data = "L2.fti"
model = "middle.fti"
sign = -1
offset = "fti_offset"
TOML
cat >back.toml <<TOML
$model
$fit
parameter_table = "tabs/parameters.tsv"
[fit.petab]
observables = "tabs/observables.tsv"
measurements = "tabs/measurements.tsv"
conditions = "tabs/conditions.tsv"
TOML
"$PHASMID" petab fit.toml -o tabs -q || { echo "FAIL petab fit.toml"; exit 1; }
"$PHASMID" fit fit.toml -o a.h5 -q; rc_a=$?
"$PHASMID" fit back.toml -o b.h5 -q; rc_b=$?
[ $rc_b = $rc_a ] && [ -e a.h5 ] && [ -e b.h5 ] || { echo "FAIL fits: exit $rc_a and $rc_b"; exit 1; }
/usr/bin/python3 - <<'PY' || fail=1
import h5py, numpy as np
a, b = h5py.File("a.h5"), h5py.File("b.h5")
for k in ("residual_labels", "residuals", "estimate", "standard_error", "initial_cost", "final_cost"):
    x, y = a["/fit/" + k][()], b["/fit/" + k][()]
    same = (x == y).all() if k == "residual_labels" else np.array_equal(x, y, equal_nan=True)
    assert same, (k, x, y)
n = len(a["/fit/residuals"])
assert n == 3 * 20 + 2 + 2 + 20 + 2, n  # a: three profiles, the noise's two, period, duty; b: one profile, period, duty
for c in ("a", "b"):
    assert a["/fit/conditions/%s/middle.thc.cpg.epsilon" % c][()] == b["/fit/conditions/%s/middle.thc.cpg.epsilon" % c][()]
print("ok round trip: %d residuals, estimates and costs identical" % n)
PY
"$PHASMID" petab back.toml -o tabs2 -q && diff -r tabs tabs2 >/dev/null && echo "ok: the tables read back write the same tables" ||
  { echo "FAIL: tables differ after the round trip"; diff -r tabs tabs2 | head; fail=1; }

# Malformed tables: one line naming the file and line, no output.
refused() {  # NAME EXPECTED: back.toml on tabs as edited
  local err
  err=$("$PHASMID" fit back.toml -o bad.h5 -q 2>&1)
  if [ "$err" = "phasmid: error: $2" ] && [ ! -e bad.h5 ]; then echo "ok refused: $1"
  else echo "FAIL $1: '$err'"; fail=1; fi
  rm -rf tabs && cp -r tabs2 tabs
}
sed -i '3s/\t[0-9.e+-]*\t\([0-9.e+-]*\)$/\t1.5\t\1/' tabs/measurements.tsv
refused "time off a bin centre" \
  "tabs/measurements.tsv:2: leg L2 under condition 'a': 'L2_thc_a' at time 1.5 ms is not the centre of phase bin 1 of 20 (time = phase x the period measurement)"
sed -i '2s/1 \* //' tabs/observables.tsv
refused "formula" \
  "tabs/observables.tsv:2: observableFormula '1 * middle.thc + -60' is not 'sign * scale * <leg>.<joint> + offset' (sign 1 or -1), period_ms(<leg>) or duty_factor(<leg>)"
sed -i '2s/^L2_thc_a/L2_nope/' tabs/measurements.tsv
refused "unknown observable" "tabs/measurements.tsv:2: observable 'L2_nope' is not in the observable table"
sed -i '$s/\tinf\t/\t7\t/' tabs/measurements.tsv
refused "steady measurement at a time" \
  "tabs/measurements.tsv:$(wc -l <tabs2/measurements.tsv): a period or duty factor is measured on the steady gait: time must be inf"
printf 'conditionId\tmiddle.thc.cpg.epsilon\na\teps_a\na\teps_b\n' >tabs/conditions.tsv
refused "condition twice" "tabs/conditions.tsv:3: condition 'a' listed twice"
sed -e 's/^\[fit.parameters\]/[[fit.feature]]\nname = "middle.fti.period_ms"\nvalue = 600.0\ntolerance = 1.0\n&/' fit.toml >feature.toml
err=$("$PHASMID" petab feature.toml -o tabs3 -q 2>&1)
if [ "$err" = "phasmid: error: feature.toml:13: PEtab tables hold recordings ([[fit.recording]]) only, not feature targets" ] && [ ! -e tabs3 ]
then echo "ok refused: a feature target in PEtab"; else echo "FAIL feature target: '$err'"; fail=1; fi
[ $fail = 0 ] && echo "petab: ok"
exit $fail
