# Sourced by corpus.test.sh: valid inputs the cases start from, made once in $fixtures.
# sim.toml: a short run of the FTi mechanics; sweep.toml: a 4-point sweep of it; run.h5, fit.h5
# and sweep.h5 (with a journal of two points, sweep.h5.journal) written by phasmid itself.
cat >"$fixtures/sim.toml" <<'TOML'
[model]
type = "mechanical_joint"
leg = "middle"
joint = "fti"
start_phase = "flexion"
[simulation]
t_end_ms = 300
output_dt_ms = 1.0
rtol = 1e-6
atol = 1e-6
TOML
cp "$fixtures/sim.toml" "$fixtures/sweep.toml"
cat >>"$fixtures/sweep.toml" <<'TOML'
[sweep]
design = "grid"
[[sweep.parameter]]
name = "middle.fti.b_v"
values = [10.0, 12.0, 14.0, 16.0]
TOML
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
