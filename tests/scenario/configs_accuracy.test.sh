#!/usr/bin/env bash
# Issue #43's accuracy gate on every shipped config: `phasmid simulate` at the config's own
# settings (for most configs the model kind's default integration) gives features within
# 0.01 ms and 0.01 deg of a tight reference, CVODES BDF at rtol = atol = 1e-10 on the whole
# system (the config's [simulation] with every solver key replaced, the run times kept).
# Dimensionless features (fractions and ratios of durations, phase lags in periods) within
# TOL_1 = 1e-4: a duration off by 0.01 ms moves a fraction of a period of >= 200 ms by at most
# 0.01/200 = 5e-5, and a ratio of two such durations by twice that; phase lags are compared
# modulo 1 (a lag near 0 wraps to near 1). 0/1 indicators must be equal. Configs whose kind
# takes no [simulation] (Cruse 1980, the analytic test functions) integrate nothing and are
# skipped.
# Also: no config sets a solver key (anything in [simulation] but t_end_ms, output_dt_ms,
# discard_ms, or [simulation.expert]) without a comment on the same or the previous line (a
# comment before a block of solver keys covers the block).
# Usage: configs_accuracy.test.sh PHASMID SOURCE_DIR [CONFIG_NAME ...]
set -u
PHASMID=$1
SRC=$2
shift 2
only=$#
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
checked=0
names=("$@")
[ ${#names[@]} -gt 0 ] || for cfg in "$SRC"/configs/*.toml; do names+=("$(basename "$cfg" .toml)"); done

# Solver keys need a reason: a comment on the key's line or the line before it.
/usr/bin/python3 - "$SRC"/configs/*.toml <<'PY' || fail=1
import re, sys
bad = 0
for path in sys.argv[1:]:
    # covered: the previous line is a comment, or a solver key that a comment covers (one
    # comment before rtol and atol covers both).
    section, covered = None, False
    for no, line in enumerate(open(path), 1):
        s = line.strip()
        if not s:
            continue
        m = re.match(r"^\[([^\]]+)\]", s)
        key_line = not m and section in ("simulation", "simulation.expert") and re.match(r"^[A-Za-z_\"]", s)
        solver_key = False
        if m:
            section = m.group(1)
        elif key_line:
            key = re.split(r"\s*=", s)[0].strip('"')
            solver_key = section == "simulation.expert" or key not in ("t_end_ms", "output_dt_ms", "discard_ms")
            if solver_key and "#" not in s and not covered:
                print(f"FAIL {path}:{no}: solver key '{key}' without a comment saying why")
                bad = 1
        covered = s.startswith("#") or (solver_key and ("#" in s or covered))
sys.exit(bad)
PY

# The config with its [simulation] solver keys replaced by the tight reference's.
reference_config() {
  /usr/bin/python3 - "$1" <<'PY'
import re, sys
out, section = [], None
for line in open(sys.argv[1]):
    s = line.strip()
    m = re.match(r"^\[([^\]]+)\]", s)
    if m:
        section = m.group(1)
        if section == "simulation.expert":
            continue
        out.append(line)
        if section == "simulation":
            out.append('rtol = 1e-10\natol = 1e-10\nintegrator = "cvodes_bdf"\n')
        continue
    if section == "simulation.expert":
        continue
    if section == "simulation" and re.match(r"^[A-Za-z_]", s) and \
            re.split(r"\s*=", s)[0] not in ("t_end_ms", "output_dt_ms", "discard_ms"):
        continue
    out.append(line)
text = "".join(out)
if not re.search(r"^\[simulation\]", text, re.M):
    text += '\n[simulation]\nrtol = 1e-10\natol = 1e-10\nintegrator = "cvodes_bdf"\n'
text += '\n[simulation.expert]\npartitioning = "whole"\n'
sys.stdout.write(text)
PY
}

for name in "${names[@]}"; do
  cfg="$SRC/configs/$name.toml"
  reference_config "$cfg" >"$tmp/$name.ref.toml"
  if ! "$PHASMID" simulate "$tmp/$name.ref.toml" -q --json -o "$tmp/ref.h5" >"$tmp/ref.json" 2>"$tmp/err"; then
    if grep -q "does not apply to model type" "$tmp/err"; then echo "skip $name (its kind takes no [simulation])"; continue; fi
    echo "FAIL reference of $name: $(cat "$tmp/err")"; fail=1; continue
  fi
  if ! "$PHASMID" simulate "$cfg" -q --json -o "$tmp/run.h5" >"$tmp/run.json" 2>"$tmp/err"; then
    echo "FAIL simulate $name: $(cat "$tmp/err")"; fail=1; continue
  fi
  checked=$((checked + 1))
  /usr/bin/python3 - "$name" "$tmp/run.json" "$tmp/ref.json" <<'PY' || fail=1
import json, math, sys
name, run, ref = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
want = {f["name"]: f for f in ref}
TOL = {"ms": 0.01, "deg": 0.01, "1": 1e-4}
worst, bad = {}, []
for f in run:
    r = want.get(f["name"])
    if r is None:
        bad.append(f"{f['name']} not in the reference")
        continue
    a, b = f["value"], r["value"]
    if a is None or b is None:
        if (a is None) != (b is None):
            bad.append(f"{f['name']}: {a} against the reference's {b}")
        continue
    d = abs(a - b)
    if f["name"].endswith("phase_lag"):
        d = min(d, abs(1 - d))
    unit = f["unit"]
    tol = TOL.get(unit, 0.0)
    if d > tol:
        bad.append(f"{f['name']} = {a:.6f} {unit}, reference {b:.6f}: off by {d:.3g} (> {tol:g})")
    if unit in TOL:
        worst[unit] = max(worst.get(unit, 0.0), d)
margins = ", ".join(f"{u} {worst[u]:.2g}" for u in ("ms", "deg", "1") if u in worst)
if bad:
    print(f"FAIL {name}: " + "; ".join(bad))
    sys.exit(1)
print(f"ok {name}: largest differences {margins}")
PY
done
[ "$only" -gt 0 ] || [ "$checked" -ge 20 ] || { echo "FAIL: only $checked configs compared"; fail=1; }
exit $fail
