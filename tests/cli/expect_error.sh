# Sourced by CLI script tests: the error contract of docs/cli.md. Needs $tmp, $fail, $pass.
# expect_error DESCRIPTION EXPECTED_SUBSTRING COMMAND...: the command must exit non-zero with
# exactly one line on stderr containing EXPECTED_SUBSTRING.
expect_error() {
  local desc="$1" want="$2"; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  local lines; lines=$(wc -l <"$tmp/err")
  if [ $rc -eq 0 ] || ! grep -q -- "$want" "$tmp/err" || [ "$lines" -ne 1 ]; then
    echo "FAIL: $desc (rc=$rc, stderr: $(cat "$tmp/err"))"; fail=$((fail+1))
  else pass=$((pass+1)); fi
}
