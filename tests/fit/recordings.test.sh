#!/usr/bin/env bash
# phasmid steps on synthetic trials in the Stick Insect Locomotion database's layout
# (tests/fixtures/locomotion_trial.py): every leg's angles are known functions of the step
# phase plus a constant offset per step, with known periods and duty factors. The summary
# must give back the median period and the duty factor exactly, the phase profile to linear
# interpolation's error bound, the per-bin SD as the offsets' SD; the MAT file and its CSV
# export must give the same summary; /steps in HDF5 must hold what --json prints.
set -euo pipefail
PHASMID=$1; SRC=$2
/usr/bin/python3 -c 'import scipy, h5py' 2>/dev/null || { echo "SKIP: Debian's python3 has no scipy/h5py"; exit 0; }
d=$(mktemp -d); trap 'rm -rf "$d"' EXIT
trial() { /usr/bin/python3 "$SRC/tests/fixtures/locomotion_trial.py" "$@"; }

check() {  # NAME RATE PERIODS(frames) DUTY NOISE
  local name=$1 rate=$2 periods=$3 duty=$4 noise=$5
  trial "$d/$name.mat" --rate "$rate" --periods "$periods" --duty "$duty" --noise "$noise" --seed 7 \
        --csv "$d/$name.csv" --expect >"$d/$name.expect.json"
  "$PHASMID" steps "$d/$name.mat" --json -o "$d/$name.h5" >"$d/$name.json"
  "$PHASMID" steps "$d/$name.csv" --json >"$d/$name.csv.json"
  /usr/bin/python3 - "$d/$name" "$rate" <<'PY'
import json, sys
import h5py, numpy as np
base, rate = sys.argv[1], float(sys.argv[2])
got, exp, csv = (json.load(open(base + s)) for s in (".json", ".expect.json", ".csv.json"))
prof = {"thc": lambda p: 10 - 25 * np.cos(2 * np.pi * p), "ctr": lambda p: 40 + 15 * np.sin(2 * np.pi * p),
        "fti": lambda p: 110 - 30 * np.cos(2 * np.pi * p) + 10 * np.sin(4 * np.pi * p)}
curv = {"thc": 25 * 4 * np.pi**2, "ctr": 15 * 4 * np.pi**2, "fti": 30 * 4 * np.pi**2 + 10 * 16 * np.pi**2}
h5 = h5py.File(base + ".h5", "r")
assert sorted(got) == ["L1", "L2", "L3", "R1", "R2", "R3"], sorted(got)
for leg, e in exp.items():
    g = got[leg]
    assert (len(g["steps"]), g["kept"]) == (e["steps"], e["kept"]), (leg, len(g["steps"]), g["kept"], e)
    assert abs(g["median_period_ms"] - e["median_period_ms"]) < 1e-9, (leg, g["median_period_ms"], e)
    assert abs(g["duty_factor"] - e["duty_factor"]) < 1e-12, (leg, g["duty_factor"], e)
    shortest = min(s["next_touchdown_ms"] - s["touchdown_ms"] for s in g["steps"] if not s["dropped"])
    h = 1000 / rate / shortest  # one frame in phase units
    phase = np.array(g["phase"])
    # A bin whose interpolation reaches the next touchdown's sample mixes in the next step's
    # offset (the synthetic angles jump there by construction); with offsets, those bins are
    # left out.
    inside = (1 - phase) / h >= 1 if e["offset_sd"] else np.ones(len(phase), bool)
    for joint, f in prof.items():
        ch = g["channels"][leg + "." + joint]
        bound = curv[joint] * h * h / 8
        err = np.abs(np.array(ch["mean_deg"]) - f(phase) - e["offset_mean"])[inside].max()
        assert err <= bound, (leg, joint, "mean", err, bound)
        if e["offset_sd"] is not None:
            err = np.abs(np.array(ch["sd_deg"]) - e["offset_sd"])[inside].max()
            assert err <= 2 * bound, (leg, joint, "sd", err, 2 * bound)
        assert np.array_equal(h5["steps/%s/mean_deg/%s.%s" % (leg, leg, joint)][()], np.array(ch["mean_deg"]))
        # The CSV's times are the MAT file's frames printed in decimal: the same to rounding.
        assert np.allclose(csv[leg]["channels"][leg + "." + joint]["mean_deg"], ch["mean_deg"], rtol=0, atol=1e-9), (leg, joint, "csv != mat")
    assert h5["steps/" + leg].attrs["median_period_ms"] == g["median_period_ms"]
    assert abs(csv[leg]["median_period_ms"] - g["median_period_ms"]) < 1e-9 and abs(csv[leg]["duty_factor"] - g["duty_factor"]) < 1e-12
print("ok", base.rsplit("/", 1)[-1], {leg: (g["median_period_ms"], round(g["duty_factor"], 4), g["kept"]) for leg, g in got.items()})
PY
}

# The database's rate, periods near the animals' (0.8-0.9 s), no noise: exact profiles.
check exact 200 160,180,170 0.7 0
# Step-to-step offsets (SD 2 deg) and another frame rate and duty factor.
check noisy 100 70,95,80,88 0.62 2
# A table on the terminal names every leg and the dropped steps.
"$PHASMID" steps "$d/noisy.mat" --leg L2 >"$d/table.txt"
grep -q '^L2 ' "$d/table.txt" && grep -q 'dropped L2 step 1 .*: start transient' "$d/table.txt" \
  || { cat "$d/table.txt"; echo "FAIL: table"; exit 1; }
# A phasmid run is summarised the same way (touchdowns from /trajectory/footfall): on the
# middle leg's steady gait the median period and duty factor are the located-event features
# to within the 1 ms output grid the footfall is sampled on (two touchdowns: 2 ms).
sed -e 's/^thc_table = "A.17"/thc_table = "A.17"\nmotoneuron = "rate"/' -e 's/^t_end_ms = .*/t_end_ms = 6000/' \
  "$SRC/configs/middle_leg_forward.toml" >"$d/leg.toml"
"$PHASMID" simulate "$d/leg.toml" -q -o "$d/leg.h5"
"$PHASMID" steps "$d/leg.h5" --discard-steps 4 --json >"$d/leg.json"
"$PHASMID" features "$d/leg.h5" --json >"$d/leg_features.json"
/usr/bin/python3 - "$d" <<'PY'
import json, sys
d = sys.argv[1]
s = json.load(open(d + "/leg.json"))["middle"]
f = {x["name"]: x["value"] for x in json.load(open(d + "/leg_features.json"))}
assert s["kept"] >= 4, s["kept"]
assert abs(s["median_period_ms"] - f["middle.step_period_ms"]) <= 2.0, (s["median_period_ms"], f["middle.step_period_ms"])
assert abs(s["duty_factor"] - f["middle.duty_factor"]) <= 2.0 / f["middle.step_period_ms"] * 2, (s["duty_factor"], f["middle.duty_factor"])
print("ok run", s["median_period_ms"], f["middle.step_period_ms"], s["duty_factor"], f["middle.duty_factor"])
PY
echo "recordings: ok"
