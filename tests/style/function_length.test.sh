#!/usr/bin/env bash
# No function in src/ over 120 lines unless the comment right above its signature says why
# (`long:`); docs/architecture.md, "Function length". The scanner is checked first on
# fixtures it must read right: a long function with and without the mark, braces in strings,
# comments and raw strings, a constructor with braced member initialisers, class members.
set -u
PHASMID="$1"; SRC="$2"
CHECK="$SRC/tests/style/function_length.py"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
py() { /usr/bin/python3 "$CHECK" "$@"; }
body() { for i in $(seq "$1"); do echo "  x += $i;"; done; }

mkdir "$tmp/fix"
{
  echo 'namespace a {'
  echo 'int unmarked(int x) {'
  echo '  const char* s = "} { \" }"; char c = '"'"'}'"'"';  // } {'
  echo '  /* { */ auto r = R"x(}})x";'
  body 120
  echo '  return x;'
  echo '}'
  echo '// long: one table, kept in one piece'
  echo 'int marked(int x) {'
  body 125
  echo '  return x;'
  echo '}'
  echo 'struct S {'
  echo '  int a_, b_;'
  echo ' public:'
  echo '  S() : a_(1), b_{2} {'
  body 121
  echo '  }'
  echo '  int short_one() const { return a_; }'
  echo '};'
  echo 'const int table[] = {1, 2, 3};'
  echo 'int short_two() { return 10'"'"'000; }'
  echo '}  // namespace a'
} >"$tmp/fix/long.cpp"
out=$(py "$tmp/fix"); rc=$?
expect="$tmp/fix/long.cpp:2: unmarked (125 lines)
$tmp/fix/long.cpp:259: S (123 lines)"
if [ $rc -ne 1 ] || [ "$out" != "$expect" ]; then
  echo "FAIL scanner on fixtures: rc=$rc, got:"; echo "$out"; echo "expected:"; echo "$expect"; fail=1
fi
out=$(py "$tmp/fix" --all)
echo "$out" | grep -q "long.cpp:128: marked (128 lines, marked long:)" || { echo "FAIL --all does not list the marked function: $out"; fail=1; }
printf 'void f() {\n  if (x) {\n}\n' >"$tmp/fix/open.cpp"
py "$tmp/fix" >/dev/null; [ $? -eq 2 ] || { echo "FAIL unbalanced braces not reported with status 2"; fail=1; }

out=$(py "$SRC/src"); rc=$?
if [ $rc -ne 0 ]; then
  echo "FAIL functions over 120 lines in src/ without a 'long:' comment above the signature:"
  echo "$out"
  fail=1
fi
[ $fail -eq 0 ] && echo "PASS function length"
exit $fail
