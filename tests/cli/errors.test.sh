#!/usr/bin/env bash
# CLI contract: bad input gives exit != 0, one line on stderr naming file/line/parameter, and
# no output file left behind.
set -u
PHASMID="$1"; SRC="$2"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0; pass=0
source "$SRC/tests/cli/expect_error.sh"
expect_error "unknown --set parameter" "unknown parameter 'middle.fti.bv'" \
  "$PHASMID" simulate "$SRC/configs/fti_mechanical.toml" --set middle.fti.bv=3 -o "$tmp/a.h5" -q
[ -e "$tmp/a.h5" ] || [ -e "$tmp/a.h5.tmp" ] && { echo "FAIL: output left behind"; fail=$((fail+1)); }
expect_error "impossible value" "impossible value -1" \
  "$PHASMID" simulate "$SRC/configs/fti_mechanical.toml" --set middle.fti.b_v=-1 -o "$tmp/b.h5" -q
printf '[model]\ntype = "mechanical_joint"\n[simulation\nt_end_ms = 5\n' >"$tmp/bad.toml"
expect_error "malformed config names file:line" "bad.toml:3" "$PHASMID" simulate "$tmp/bad.toml" -o "$tmp/c.h5"
printf '[model]\ntype = "mechanical_joint"\n[parameters]\n"middle.fti.nope" = 1\n' >"$tmp/unk.toml"
expect_error "unknown parameter in config names file:line" "unk.toml:4" "$PHASMID" params "$tmp/unk.toml"
expect_error "missing config" "no such config" "$PHASMID" params "$tmp/missing.toml"
printf '[model]\ntype = "leg"\nstart_ms = -5\n' >"$tmp/start.toml"
expect_error "negative start_ms names file:line" "start.toml:3.*'start_ms' must be a number >= 0" "$PHASMID" params "$tmp/start.toml"
printf '[model]\ntype = "three_legs"\nstart_ms = 100\n' >"$tmp/start3.toml"
expect_error "start_ms on three legs names file:line" "start3.toml:3.*unknown key 'start_ms' in \[model\]" "$PHASMID" params "$tmp/start3.toml"
printf '[model]\ntype = "three_legs"\ncoupling_gate = "always"\n' >"$tmp/gate.toml"
expect_error "unknown coupling_gate names file:line and the choices" "gate.toml:3.*unknown coupling_gate 'always' (expected target_swing or source_contact)" \
  "$PHASMID" params "$tmp/gate.toml"
printf '[model]\ntype = "three_legs"\n[[triggers]]\nset = "gait.switch_ms"\nevent = "hind.landing"\n' >"$tmp/trig.toml"
expect_error "unknown trigger event names file:line" "trig.toml:5: unknown event 'hind.landing'" \
  "$PHASMID" simulate "$tmp/trig.toml" -o "$tmp/e.h5" -q
printf '[model]\ntype = "three_legs"\n[[triggers]]\nset = "gait.switch_ms"\nevent = "front.touchdown"\nin_stance = ["hnd"]\n' >"$tmp/stance.toml"
expect_error "unknown in_stance leg names file:line and the legs" "stance.toml:6: unknown leg 'hnd' in \[\[triggers\]\] 'in_stance' (expected one of front, middle, hind)" \
  "$PHASMID" simulate "$tmp/stance.toml" -o "$tmp/e2.h5" -q
[ -e "$tmp/e2.h5" ] && { echo "FAIL: output left after a config error"; fail=$((fail+1)); }
printf '[model]\ntype = "three_legs"\n[[triggers]]\nset = "gait.switch_ms"\nevent = "front.touchdown"\nin_stance = "hind"\n' >"$tmp/stance2.toml"
expect_error "in_stance not a list names file:line" "stance2.toml:6: 'in_stance' must be an array of leg names" \
  "$PHASMID" params "$tmp/stance2.toml"
printf '[model]\ntype = "three_legs"\n[[triggers]]\nset = "gait.switch_ms"\nevent = "front.touchdown"\nin_stance = ["hind", 2]\n' >"$tmp/stance3.toml"
expect_error "in_stance with a non-string names file:line" "stance3.toml:6: 'in_stance' must be an array of leg names" \
  "$PHASMID" params "$tmp/stance3.toml"
printf '[model]\ntype = "three_legs"\n[[triggers]]\nset = "gait.switch_ms"\nevent = "hind.liftoff"\n[sensitivity]\nparameters = ["gait.switch_ms"]\n' >"$tmp/trigsens.toml"
expect_error "no sensitivity to a triggered command time" "no sensitivity to gait.switch_ms: it is set by the \[\[triggers\]\] event hind.liftoff" \
  "$PHASMID" sensitivity "$tmp/trigsens.toml" -o "$tmp/f.h5"
printf '[model]\ntype = "three_legs"\n[simulation]\n[simulation.expert]\npartitioning = "yes"\n' >"$tmp/part.toml"
expect_error "partitioning must be one of its names, names file:line" "part.toml:5: 'partitioning' must be \"whole\", \"joints\" or \"neurons\"" \
  "$PHASMID" simulate "$tmp/part.toml" -o "$tmp/g.h5" -q
printf '[model]\ntype = "three_legs"\n[simulation]\npartitioned = true\n' >"$tmp/old.toml"
expect_error "a key of earlier versions says where it went" "old.toml:4: 'partitioned' is no longer a \[simulation\] key; the model kind chooses it (docs/solver.md), or set \[simulation.expert\] partitioning" \
  "$PHASMID" simulate "$tmp/old.toml" -o "$tmp/g.h5" -q
printf '[model]\ntype = "three_legs"\n[simulation]\nt_end = 10\n' >"$tmp/unk2.toml"
expect_error "an unknown key lists the keys and the expert table" "unk2.toml:4: unknown key 't_end' in \[simulation\] (allowed: atol, discard_ms, expert, integrator, max_step_ms, output_dt_ms, rtol, t_end_ms)" \
  "$PHASMID" simulate "$tmp/unk2.toml" -o "$tmp/g.h5" -q
printf '[model]\ntype = "single_joint"\n[simulation]\n[simulation.expert]\nthreads = 2\npartitioning = "neurons"\n' >"$tmp/neur.toml"
expect_error "partitioning = neurons on two threads, names file:line" "neur.toml:3: \[simulation\]: expert.partitioning = \"neurons\" runs on one thread (expert.threads = 1)" \
  "$PHASMID" simulate "$tmp/neur.toml" -o "$tmp/n.h5" -q
printf '[model]\ntype = "single_joint"\n[simulation]\nt_end_ms = 10\n[simulation.expert]\natol_by_unit = { "rad/ms" = 1e-6 }\n' >"$tmp/unit.toml"
expect_error "atol_by_unit with a unit no state has" "no state of this model has unit 'rad/ms' (its units: 'mV', '1', 'rad', 'rad/s')" \
  "$PHASMID" simulate "$tmp/unit.toml" -o "$tmp/u.h5" -q
[ -e "$tmp/u.h5" ] && { echo "FAIL: output left after the atol_by_unit error"; fail=$((fail+1)); }
expect_error "ratios bad angle" "not a number" "$PHASMID" ratios --joint fti --angles 45,x
expect_error "solver failure is reported" "CVODES failed" \
  "$PHASMID" simulate "$SRC/configs/fti_mechanical.toml" --set middle.fti.l_E0=0.1 -o "$tmp/d.h5" -q
[ -e "$tmp/d.h5" ] && { echo "FAIL: output left after solver failure"; fail=$((fail+1)); }
# compiled_rhs where it cannot be had: one warning line, the run completes with the generic
# right-hand side (a model kind without generated code; a cache directory that cannot be made:
# the spiking joint's default, which compiles, then runs the generic evaluation, the same bits).
printf '[model]\ntype = "mechanical_joint"\n[simulation]\nt_end_ms = 50\n[simulation.expert]\ncompiled_rhs = true\n' >"$tmp/cr.toml"
if "$PHASMID" simulate "$tmp/cr.toml" -o "$tmp/cr.h5" -q 2>"$tmp/err" && [ "$(wc -l <"$tmp/err")" -eq 1 ] \
   && grep -q "warning: compiled_rhs: this model kind has no compiled right-hand side" "$tmp/err"; then pass=$((pass+1))
else echo "FAIL: compiled_rhs on a mechanical joint ($(cat "$tmp/err"))"; fail=$((fail+1)); fi
sed -e 's/^t_end_ms *=.*/t_end_ms = 100/' -e 's/^discard_ms *=.*/discard_ms = 0/' "$SRC/configs/single_joint_fti.toml" >"$tmp/sj.toml"
cp "$tmp/sj.toml" "$tmp/sjg.toml"
printf '[simulation.expert]\ncompiled_rhs = false\n' >>"$tmp/sjg.toml"
"$PHASMID" simulate "$tmp/sjg.toml" -o "$tmp/sj.h5" -q
if PHASMID_CACHE_DIR=/proc/phasmid-no-cache "$PHASMID" simulate "$tmp/sj.toml" -o "$tmp/sjc.h5" -q 2>"$tmp/err" \
   && [ "$(wc -l <"$tmp/err")" -eq 1 ] \
   && grep -q "warning: compiled_rhs: cannot create the cache directory /proc/phasmid-no-cache" "$tmp/err" \
   && h5diff -q "$tmp/sj.h5" "$tmp/sjc.h5" /trajectory/states; then pass=$((pass+1))
else echo "FAIL: the default's compiled_rhs without a cache directory ($(cat "$tmp/err"))"; fail=$((fail+1)); fi
# and the good path: ratios JSON carries the required fields
out=$("$PHASMID" ratios --joint fti --angles 45,110 --json)
echo "$out" | grep -q '"angle_deg": 45' && echo "$out" | grep -q '"ratio"' && echo "$out" | grep -q '"joint": "fti"' \
  && pass=$((pass+1)) || { echo "FAIL: ratios --json fields"; fail=$((fail+1)); }
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
