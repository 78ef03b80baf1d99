#!/usr/bin/env bash
# simulate's memory does not grow with t_end_ms (docs/reliability.md "Memory"): the samples go
# into the file as they are reached. The prescribed FTi mechanics (configs/fti_mechanical.toml)
# run for 6 s and for 600 s (600 001 samples, 1 s of CPU); the peak resident memory of the long
# run may exceed the short run's by at most 8 MiB. Keeping the trajectory in memory until the
# file is written (phasmid before the streaming) adds about 35 MB here.
# Usage: streamed_memory.test.sh PHASMID SOURCE_DIR
set -u
PHASMID=$1 SRC=$2
[ -x /usr/bin/time ] || { echo "FAIL: /usr/bin/time missing (apt-get install time)"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
limit_kb=8192

peak_kb() {  # t_end_ms -> peak resident set of simulate, KiB
  sed "s/^t_end_ms = .*/t_end_ms = $1/" "$SRC/configs/fti_mechanical.toml" >"$tmp/$1.toml"
  /usr/bin/time -o "$tmp/$1.rss" -f %M "$PHASMID" simulate "$tmp/$1.toml" -o "$tmp/$1.h5" -q ||
    { echo "FAIL: simulate t_end_ms = $1"; fail=1; }
  cat "$tmp/$1.rss"
}

short=$(peak_kb 6000)
long=$(peak_kb 600000)
samples=$(h5ls "$tmp/600000.h5/trajectory/time" | sed -n 's/.*{\([0-9]*\)[/}].*/\1/p')
[ "$samples" = 600001 ] || { echo "FAIL: /trajectory/time has '$samples' samples, not 600001"; fail=1; }
growth=$((long - short))
echo "peak RSS: ${short} KiB for 6 s, ${long} KiB for 600 s (+${growth} KiB, limit ${limit_kb})"
[ "$growth" -le "$limit_kb" ] || { echo "FAIL: memory grows with t_end_ms"; fail=1; }
[ $fail -eq 0 ] && echo "streamed memory: ok"
exit $fail
