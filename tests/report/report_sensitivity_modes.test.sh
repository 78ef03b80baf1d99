#!/usr/bin/env bash
# The report of a steady-cycle sensitivity file over all 117 parameters of the rate single joint
# (configs/sensitivity_steady_gait.toml) draws in headless Chromium with no script error (body
# data-status="ok", data-errors empty), says what was differentiated ("Steady cycle", the
# period), draws each feature's top 15 parameters and names how many more there are, and draws
# the heat map per parameter family; a transient file says "Transient". Usage: PHASMID SOURCE_DIR
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
source "$SRC/tests/report/chromium.sh"  # $tmp (the working directory), render NAME
"$PHASMID" sensitivity "$SRC/configs/sensitivity_steady_gait.toml" -q -o steady.h5 >/dev/null || { echo "FAIL steady-cycle run"; exit 1; }
sed -e 's/t_end_ms = 4000/t_end_ms = 2000/' -e 's/discard_ms = 1500/discard_ms = 500/' \
  "$SRC/configs/sensitivity_single_joint.toml" >transient.toml
"$PHASMID" sensitivity transient.toml -q -o transient.h5 >/dev/null || { echo "FAIL transient run"; exit 1; }
expect() {  # NAME TEXT: the rendered page holds TEXT
  grep -qF -- "$2" "$1.dom" && echo "ok $1: $2" || { echo "FAIL $1: no '$2' on the page"; fail=1; }
}
render steady && {
  expect steady "Mode. Steady cycle"
  expect steady "period 512.4"
  expect steady "102 more parameters"
  expect steady "per parameter family"
}
render transient && expect transient "Mode. Transient"
exit $fail
