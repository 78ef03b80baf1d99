# Sourced by the report script tests: a scratch directory ($tmp, removed on exit, the working
# directory from here on) and render NAME, which writes NAME.html from NAME.h5 with `phasmid
# report` and dumps the page's DOM after its scripts ran into NAME.dom, failing (fail=1, one
# line) unless the page reports no script error (body data-status="ok", data-errors empty).
# Needs $PHASMID and Debian's chromium and h5py.
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -x /usr/bin/chromium ] || { echo "FAIL chromium is required (apt-get install -y chromium)"; exit 1; }
/usr/bin/python3 -c 'import h5py' || { echo "FAIL h5py for Debian's python3 is required"; exit 1; }
cd "$tmp" || exit 1
render() {
  local err body
  err=$("$PHASMID" report "$1.h5" -o "$1.html" 2>&1) || { echo "FAIL report $1: $err"; fail=1; return 1; }
  # 300 s: a hang guard only (the page's 15 s are Chromium's virtual time, not the machine's).
  timeout 300 /usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage \
    --user-data-dir="$tmp/profile" --virtual-time-budget=15000 --dump-dom "file://$tmp/$1.html" >"$1.dom" 2>/dev/null
  [ $? -eq 124 ] && { echo "FAIL $1: chromium hung"; fail=1; return 1; }
  body=$(tr '\n' ' ' <"$1.dom" | grep -o '<body[^>]*>' | head -1)
  if grep -q 'data-status="ok"' <<<"$body" && grep -q 'data-errors=""' <<<"$body"; then echo "ok $1"
  else echo "FAIL $1: $(head -c 600 <<<"$body")"; fail=1; return 1; fi
}
