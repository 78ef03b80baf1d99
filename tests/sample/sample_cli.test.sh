#!/usr/bin/env bash
# phasmid sample from the command line (docs/sampling.md): parallel tempering from the fit's
# optimum on the Section 3.1 spring-constant fit, the /sample layout checked against itself
# (shapes, bounds, log posterior = prior + likelihood, the summary = the kept draws), the
# same draws on 1 and 2 threads, and bad input with one line and no output left behind.
set -u
PHASMID="$1"; SRC="$2"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; pass=0
source "$SRC/tests/cli/expect_error.sh"
cfg="$tmp/s31.toml"
cp "$SRC/configs/fit_fti_section31.toml" "$cfg"
printf '\n[sample]\nsampler = "parallel_tempering"\ntemperatures = 4\nmax_temperature = 1000\nchains = 2\ndraws = 3000\nstart = "fit"\n' >>"$cfg"
for j in 1 2; do
  "$PHASMID" sample "$cfg" -j $j -q -o "$tmp/s$j.h5"; rc=$?
  if [ $rc -ne 0 ] && [ $rc -ne 3 ]; then echo "FAIL: sample -j $j exited $rc"; fail=$((fail+1)); fi
done
/usr/bin/python3 - "$tmp/s1.h5" "$tmp/s2.h5" <<'PY' && pass=$((pass+1)) || { echo "FAIL: /sample layout"; fail=$((fail+1)); }
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
d = a["/sample/draws"][...]
assert d.shape == (2, 3000, 4), d.shape
assert np.array_equal(d, b["/sample/draws"][...]), "threads changed the draws"
lp, ll, lpost = (a["/sample/" + k][...] for k in ("log_prior", "log_likelihood", "log_posterior"))
assert lp.shape == ll.shape == (2, 3000) and np.allclose(lpost, lp + ll, rtol=0, atol=1e-12)
names = [n.decode() for n in a["/sample/parameter_names"][...]]
assert names[0] == "middle.fti.k_E.flexion", names
lo, hi = np.array([50, 30, 400, 5]), np.array([5000, 3000, 40000, 500])  # the config's bounds
assert (d >= lo).all() and (d <= hi).all(), "a draw outside the bounds"
burn = int(a["/sample/diagnostics/burn_in"][()])
assert 3000 // 20 <= burn < 3000, burn
kept = d[:, burn:, :].reshape(-1, 4)
assert np.allclose(a["/sample/summary/mean"][...], kept.mean(axis=0), rtol=1e-12)
assert np.allclose(a["/sample/summary/sd"][...], kept.std(axis=0, ddof=1), rtol=1e-12)
assert a["/sample"].attrs["sampler"] in (b"parallel_tempering", "parallel_tempering")
betas = a["/sample/tempering/betas"][...]
assert betas.shape == (2, 4) and (betas[:, 0] == 1).all() and np.allclose(betas[:, -1], 1e-3)
assert a["/sample/diagnostics/ess"].shape == (4,) and a["/sample/diagnostics/split_rhat"].shape == (4,)
PY
nofile() { [ -e "$tmp/$1" ] || [ -e "$tmp/$1.tmp" ] && { echo "FAIL: $1 left behind"; fail=$((fail+1)); }; return 0; }
expect_error "a fit that is not a likelihood" "needs absolute_sigma = true in" \
  "$PHASMID" sample "$SRC/configs/fti_mechanical.toml" --data "$SRC/datasets/synthetic/fti_kinematics_synthetic.csv" \
  --parameters "$SRC/datasets/synthetic/fti_kinematics_params.tsv" -q -o "$tmp/e1.h5"
nofile e1.h5
cp "$SRC/configs/fit_fti_section31.toml" "$tmp/k.toml"; printf '\n[sample]\ndraw = 100\n' >>"$tmp/k.toml"
expect_error "unknown [sample] key" "k.toml:59: unknown key 'draw' in" "$PHASMID" sample "$tmp/k.toml" -q -o "$tmp/e2.h5"
nofile e2.h5
cp "$SRC/configs/fit_fti_section31.toml" "$tmp/t.toml"; printf '\n[sample]\ntemperatures = 3\n' >>"$tmp/t.toml"
expect_error "temperatures without tempering" 'temperatures > 1 needs sampler = "parallel_tempering"' \
  "$PHASMID" sample "$tmp/t.toml" -q -o "$tmp/e3.h5"
nofile e3.h5
expect_error "too few draws" "draws must be an integer in" \
  "$PHASMID" sample "$SRC/configs/fit_fti_section31.toml" --draws 5 -q -o "$tmp/e4.h5"
nofile e4.h5
printf 'parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\tobjectivePriorType\tobjectivePriorParameters\nmiddle.fti.k_E.flexion\tlog10\t50\t5000\t510\t1\tnormal\t500;-3\n' >"$tmp/p.tsv"
expect_error "a prior with a negative sd" "p.tsv:2: normal prior needs a positive second parameter" \
  "$PHASMID" sample "$SRC/configs/fit_fti_section31.toml" --parameters "$tmp/p.tsv" -q -o "$tmp/e5.h5"
nofile e5.h5
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
