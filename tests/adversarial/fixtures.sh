# Sourced by corpus.test.sh: valid inputs the cases start from, made once in $fixtures.
# sim.toml: a short run of the FTi mechanics; sweep.toml: a 4-point sweep of it; run.h5, fit.h5
# and sweep.h5 (with a journal of two points, sweep.h5.journal) written by phasmid itself.
cp "$SRC/tests/fixtures/fti_mechanics_short.toml" "$fixtures/sim.toml"
cat "$fixtures/sim.toml" "$SRC/tests/fixtures/b_v_grid.toml" >"$fixtures/sweep.toml"
cp "$SRC/datasets/synthetic/fti_kinematics_synthetic.csv" "$fixtures/kin.csv"
cp "$SRC/datasets/synthetic/fti_kinematics_synthetic_anipose.csv" "$fixtures/anipose.csv"
cp "$SRC/datasets/synthetic/fti_kinematics_params.tsv" "$fixtures/params.tsv"
sed -e "s#\.\./datasets/synthetic/#$fixtures/#" -e 's#fti_kinematics_params.tsv#params.tsv#' \
    -e 's#fti_kinematics_synthetic.csv#kin.csv#' "$SRC/configs/fit_fti_kinematic_synthetic.toml" >"$fixtures/fit.toml"
sed -e "s#\.\./datasets/synthetic/#$fixtures/#" -e 's#fti_kinematics_params.tsv#params.tsv#' \
    -e 's#fti_kinematics_synthetic_anipose.csv#anipose.csv#' "$SRC/configs/fit_fti_anipose_synthetic.toml" >"$fixtures/fit_anipose.toml"
"$PHASMID" simulate "$fixtures/sim.toml" -q -o "$fixtures/run.h5" || echo "fixture run.h5 failed"
"$PHASMID" sweep "$fixtures/sweep.toml" -q -o "$fixtures/sweep.h5" -j 1 || echo "fixture sweep.h5 failed"
"$PHASMID" sweep "$fixtures/sweep.toml" -q -o "$fixtures/part.h5" -j 1 --stop-after 2 2>/dev/null
[ -s "$fixtures/part.h5.journal" ] || echo "fixture part.h5.journal failed"
have_h5py() { /usr/bin/python3 -c 'import h5py' 2>/dev/null || { echo "SKIP: no h5py for Debian's python3"; return 1; }; }
# h5edit FILE 'python statements on f (an h5py.File opened r+)': edit a copy of a fixture.
h5edit() { have_h5py && /usr/bin/python3 -c "import h5py, numpy as np
f = h5py.File('$1', 'r+')
$2
f.close()"; }
export -f have_h5py h5edit
# cont.toml: the head of a [continuation] config of the Stuart-Landau test kind (cases append
# lines from line 7: cont 'key = value\n'); gsa.toml: the Ishigami ranges and [gsa] features
# (cases append from line 17: gsa 'N = 8\n'); part0.h5, part1.h5: the two shards of sweep.toml;
# cont.h5: a short continuation branch, for report.
cat >"$fixtures/cont.toml" <<'TOML'
[model]
type = "stuart_landau"
[continuation]
parameter = "sl.lambda"
range = [0.05, 0.03]
section_state = "sl.y"
TOML
cat >"$fixtures/gsa.toml" <<'TOML'
[model]
type = "ishigami"
[[sweep.parameter]]
name = "x1"
lower = -3.14
upper = 3.14
[[sweep.parameter]]
name = "x2"
lower = -3.14
upper = 3.14
[[sweep.parameter]]
name = "x3"
lower = -3.14
upper = 3.14
[gsa]
features = ["y"]
TOML
cont() { cp "$fixtures/cont.toml" "$in"; printf -- "$1" >>"$in"; }
gsa() { cp "$fixtures/gsa.toml" "$in"; printf -- "$1" >>"$in"; }
export -f cont gsa
for i in 0 1; do
  "$PHASMID" sweep "$fixtures/sweep.toml" -q -o "$fixtures/part$i.h5" -j 1 --shard $i/2 || echo "fixture part$i.h5 failed"
done
cont_fixture() {
  cp "$fixtures/cont.toml" "$fixtures/cont_run.toml"
  printf 'max_points = 4\ntransient_ms = 1500\nmax_period_ms = 150\n[simulation]\nrtol = 1e-8\natol = 1e-8\n' >>"$fixtures/cont_run.toml"
  "$PHASMID" continue "$fixtures/cont_run.toml" -q -o "$fixtures/cont.h5" || echo "fixture cont.h5 failed"
}
cont_fixture
# trial FILE [ARGS]: a synthetic Stick Insect Locomotion trial (tests/fixtures/locomotion_trial.py;
# --delete FIELD / --set FIELD=EXPR make it malformed); skipped without Debian's scipy.
trial() {
  /usr/bin/python3 -c 'import scipy' 2>/dev/null || { echo "SKIP: no scipy for Debian's python3"; return 1; }
  /usr/bin/python3 "$SRC/tests/fixtures/locomotion_trial.py" "$@"
}
export -f trial
