#!/usr/bin/env bash
# `phasmid report` on files with ±1e308 numbers (features, parameters, a sweep's outputs, a
# continuation branch) and with continuation special points whose columns disagree in length or
# hold NaN: the report exits 0 and the page draws in headless Chromium with no script error
# (body data-status="ok", data-errors empty; issue #42). Usage: PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
source "$SRC/tests/report/chromium.sh"  # $tmp (the working directory), render NAME
cp "$SRC/tests/fixtures/fti_mechanics_short.toml" sim.toml
cp sim.toml sweep.toml
printf '[sweep]\ndesign = "grid"\n[[sweep.parameter]]\nname = "middle.fti.b_v"\nvalues = [10.0, 12.0, 14.0]\n' >>sweep.toml
cp sweep.toml sweep2.toml  # two parameters: the features as colour maps over the plane
printf '[[sweep.parameter]]\nname = "middle.fti.inertia"\nvalues = [0.1, 0.11]\n' >>sweep2.toml
printf '[model]\ntype = "ishigami"\n' >gsa.toml
for x in x1 x2 x3; do printf '[[sweep.parameter]]\nname = "%s"\nlower = -3.14\nupper = 3.14\n' $x >>gsa.toml; done
printf '[gsa]\nN = 16\nbootstrap = 20\nfeatures = ["y"]\n' >>gsa.toml
cat >cont.toml <<'TOML'
[model]
type = "stuart_landau"
[simulation]
rtol = 1e-8
atol = 1e-8
[continuation]
parameter = "sl.lambda"
range = [0.05, 0.03]
section_state = "sl.y"
max_points = 4
transient_ms = 1500
max_period_ms = 150
TOML
"$PHASMID" simulate sim.toml -q -o run.h5 && "$PHASMID" sweep sweep.toml -q -j 1 -o sweep.h5 &&
  "$PHASMID" sweep sweep2.toml -q -j 1 -o sweep2.h5 && "$PHASMID" gsa gsa.toml -q -j 1 -o gsa.h5 &&
  "$PHASMID" continue cont.toml -q -o cont.h5 || { echo "FAIL making the inputs"; exit 1; }
edit() {  # edit COPY_OF NAME 'python on f'
  cp "$1" "$2.h5"
  /usr/bin/python3 -c "import h5py, numpy as np
f = h5py.File('$2.h5', 'r+')
$3
f.close()" || { echo "FAIL editing $2"; fail=1; }
}
edit run.h5 feature_huge 'for n in list(f["features"].keys())[:2]: f["features/" + n][...] = 1e308
n = list(f["features"].keys())[2]; f["features/" + n][...] = -1e308
f["parameters/values"][0] = 1.7976931348623157e308; f["parameters/values"][1] = -1e308'
edit sweep.h5 sweep_huge 'for n in f["sweep/features"].keys(): f["sweep/features/" + n][0] = 1e308; f["sweep/features/" + n][1] = -1e308'
edit sweep2.h5 sweep2_huge 'for n in f["sweep/features"].keys(): f["sweep/features/" + n][0] = 1e308; f["sweep/features/" + n][1] = -1e308'
edit gsa.h5 gsa_huge 'for p in ["sweep/features/y", "gsa/y/Y"]: f[p][0] = 1e308; f[p][1] = -1e308
for p in ["S1", "ST", "S1_conf", "S2", "convergence/S1"]: f["gsa/y/" + p][...] = 1e308
f["gsa/y/ST_conf"][...] = -1e308'
edit cont.h5 cont_huge 'p = f["continuation/features/period_ms"]; p[0] = 1e308; p[1] = -1e308
f["continuation/period_ms"][0] = 1e308'
edit cont.h5 cont_special 'g = f["continuation/special_points"]; del g["index"]; g["index"] = np.zeros(0)'
edit cont.h5 cont_special_nan 'g = f["continuation/special_points"]
for n in ["index", "parameter", "period_ms"]: del g[n]; g[n] = np.full(len(g["kind"]), np.nan)'
for name in feature_huge sweep_huge sweep2_huge gsa_huge cont_huge cont_special cont_special_nan; do
  render "$name"
done
grep -q 'special_points (unreadable' cont_special.html || { echo "FAIL cont_special: the special points are not listed as ignored"; fail=1; }
exit $fail
