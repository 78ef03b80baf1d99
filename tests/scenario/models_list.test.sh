#!/usr/bin/env bash
# `phasmid models` lists the walking models and, under their own heading, the analytic test
# problems (kinds with a known answer that exist to test the methods); --json says which is
# which. Usage: models_list.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$1
fail=0
tests="ishigami sobol_g stuart_landau van_der_pol relay_oscillator"
models="mechanical_joint coupled_ctr_fti single_joint leg three_legs curve_walking cruse1980"
json=$("$PHASMID" models --json) || { echo "FAIL: phasmid models --json"; exit 1; }
category() {  # the category of kind $1 in the JSON list
  /usr/bin/python3 -c 'import json,sys; print({k["type"]: k["category"] for k in json.load(sys.stdin)}.get(sys.argv[1], "absent"))' "$1" <<<"$json"
}
for k in $tests; do
  [ "$(category "$k")" = test_problem ] || { echo "FAIL: $k is not listed as a test problem"; fail=1; }
done
for k in $models; do
  [ "$(category "$k")" = model ] || { echo "FAIL: $k is not listed as a model"; fail=1; }
done
# In the text listing every test problem comes after the heading, every model before it.
text=$("$PHASMID" models) || { echo "FAIL: phasmid models"; exit 1; }
heading=$(grep -n "^Analytic test problems" <<<"$text" | cut -d: -f1)
[ -n "$heading" ] || { echo "FAIL: no 'Analytic test problems' heading"; exit 1; }
for k in $tests $models; do
  line=$(grep -n "^$k " <<<"$text" | cut -d: -f1)
  [ -n "$line" ] || { echo "FAIL: $k not in the listing"; fail=1; continue; }
  case " $tests " in
    *" $k "*) [ "$line" -gt "$heading" ] || { echo "FAIL: $k listed among the models"; fail=1; } ;;
    *) [ "$line" -lt "$heading" ] || { echo "FAIL: $k listed among the test problems"; fail=1; } ;;
  esac
done
[ $fail = 0 ] && echo "ok: $(wc -w <<<"$models") models, $(wc -w <<<"$tests") test problems apart"
exit $fail
