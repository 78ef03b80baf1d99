#!/usr/bin/env bash
# The adversarial corpus (docs/reliability.md): every case of tests/adversarial/cases/*.cases
# must keep the error contract of docs/cli.md. A .cases file starts with
#   @command <shell words run for every case, with $in, $out, $d, $PHASMID, $SRC>
#   @input <file name of $in inside the case directory>
# and then has one case per line: NAME <TAB> EXPECTED (grep -E on stderr) <TAB> SETUP (shell
# run in the case directory to create $in; helpers: w 'printf-format' writes $in).
# Each case must: exit non-zero and below 128 (no signal), print exactly one line on stderr
# matching EXPECTED, and leave no output or temporary file (the directory holds what SETUP
# made). EXPECTED "@ok" marks input a tolerant reader (report) must accept: exit 0, nothing on
# stderr, no signal (its memory bounded by the @command). How long a case takes is not checked:
# a case still running after $CASE_HANG_SECONDS (default 300 s, a hang guard, not a speed
# limit) is ended and fails as hung. Usage: corpus.test.sh PHASMID SOURCE_DIR [FILTER]
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2"); FILTER=${3:-}
CASE_HANG_SECONDS=${CASE_HANG_SECONDS:-300}
export PHASMID SRC
root=$(mktemp -d); trap 'rm -rf "$root"' EXIT
fixtures="$root/fixtures"; mkdir -p "$fixtures"; export fixtures
source "$SRC/tests/adversarial/fixtures.sh"
fail=0; pass=0; skip=0
w() { printf -- "$1" >"$in"; }
export -f w

run_case() {  # FILE NAME EXPECTED SETUP COMMAND INPUT
  local file=$1 name=$2 want=$3 setup=$4 command=$5 input=$6
  local d="$root/case"; rm -rf "$d"; mkdir -p "$d"
  local in="$d/$input" out="$d/out.h5"
  export d in out
  if ! (cd "$d" && eval "$setup") >"$root/setup.log" 2>&1; then
    if grep -q '^SKIP' "$root/setup.log"; then skip=$((skip+1)); return; fi
    echo "FAIL $file/$name: setup failed: $(head -c 300 "$root/setup.log")"; fail=$((fail+1)); return
  fi
  local before; before=$(cd "$d" && find . | sort)
  # timeout exits 124 when it ended the case (TERM, then KILL 10 s later: then 137, a signal).
  (cd "$d" && timeout -k 10 "$CASE_HANG_SECONDS" bash -c "$command") >"$root/stdout" 2>"$root/stderr" </dev/null
  local rc=$?
  local after; after=$(cd "$d" && find . | sort)
  local lines; lines=$(wc -l <"$root/stderr")
  local why=""
  if [ $rc -eq 124 ]; then
    why="hung: still running after $CASE_HANG_SECONDS s"
  elif [ "$want" = "@ok" ]; then  # a tolerant reader: succeeds, quietly, on what it can read
    [ $rc -ne 0 ] && why="exit $rc"
    [ "$lines" -ne 0 ] && why="$why; $lines lines on stderr"
  else
    [ $rc -eq 0 ] && why="exit 0"
    [ $rc -ge 128 ] && why="signal (exit $rc)"
    [ "$lines" -ne 1 ] && why="$why; $lines lines on stderr"
    grep -Eq -- "$want" "$root/stderr" || why="$why; stderr does not match '$want'"
    [ "$before" != "$after" ] && why="$why; files left: $(comm -13 <(echo "$before") <(echo "$after") | tr '\n' ' ')"
  fi
  if [ -n "$why" ]; then
    echo "FAIL $file/$name:${why#;} -- stderr: $(head -c 400 "$root/stderr")"; fail=$((fail+1))
  else pass=$((pass+1)); fi
}

for cases in "$SRC"/tests/adversarial/cases/*.cases; do
  file=$(basename "$cases" .cases)
  command=$(sed -n 's/^@command //p' "$cases")
  input=$(sed -n 's/^@input //p' "$cases")
  n=0
  while IFS=$'\t' read -r name want setup; do
    case "$name" in ''|'#'*|'@'*) continue;; esac
    [ -n "$FILTER" ] && [[ "$file/$name" != *$FILTER* ]] && continue
    n=$((n+1))
    run_case "$file" "$name" "$want" "$setup" "$command" "$input"
  done <"$cases"
  echo "$file: $n cases"
done
echo "$pass passed, $fail failed, $skip skipped"
[ $fail -eq 0 ]
