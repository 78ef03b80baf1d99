#!/usr/bin/env bash
# Faults of the adversarial corpus (docs/reliability.md): a full disk, a read-only directory,
# SIGKILL and SIGINT in the middle of a run, two writers on one output. Usage:
# faults.test.sh PHASMID SOURCE_DIR. Mounting a tmpfs needs root; without it those cases skip.
set -u
PHASMID=$(readlink -f "$1"); SRC=$(readlink -f "$2")
tmp=$(mktemp -d); mnt="$tmp/mnt"; mkdir -p "$mnt"
cleanup() { mountpoint -q "$mnt" && umount "$mnt"; rm -rf "$tmp"; }
trap cleanup EXIT
fail=0; pass=0; skip=0
ok() { pass=$((pass+1)); }
bad() { echo "FAIL: $*"; fail=$((fail+1)); }
one_line_error() {  # RC STDERR_FILE PATTERN
  [ "$1" -ne 0 ] && [ "$1" -lt 128 ] && [ "$(wc -l <"$2")" -eq 1 ] && grep -Eq -- "$3" "$2"
}
FTI="$SRC/configs/single_joint_fti.toml"   # 9 s of walking, about 2 MB of trajectory

# Full disk: a 1 MB tmpfs. One line, no crash in HDF5's close, nothing left on the disk.
if mount -t tmpfs -o size=1m tmpfs "$mnt" 2>/dev/null; then
  "$PHASMID" simulate "$FTI" -o "$mnt/o.h5" -q 2>"$tmp/err"; rc=$?
  one_line_error $rc "$tmp/err" "HDF5: cannot write" && ok || bad "full disk: rc=$rc, stderr: $(cat "$tmp/err")"
  [ -z "$(ls -A "$mnt")" ] && ok || bad "full disk: left $(ls -A "$mnt")"
  # Read-only directory (a read-only tmpfs: root ignores file modes).
  umount "$mnt"; mount -t tmpfs -o ro,size=1m tmpfs "$mnt"
  "$PHASMID" simulate "$SRC/configs/fti_mechanical.toml" -o "$mnt/o.h5" -q 2>"$tmp/err"; rc=$?
  one_line_error $rc "$tmp/err" "cannot create HDF5 file .*o.h5.tmp" && ok || bad "read-only: rc=$rc, stderr: $(cat "$tmp/err")"
  "$PHASMID" report "$SRC/tests/adversarial/faults.test.sh" -o "$mnt/r.html" 2>"$tmp/err"; rc=$?
  one_line_error $rc "$tmp/err" "not an HDF5 file" && ok || bad "read-only report: rc=$rc, stderr: $(cat "$tmp/err")"
  umount "$mnt"
else
  echo "SKIP: cannot mount a tmpfs (not root?): full disk and read-only directory untested"; skip=$((skip+2))
fi

# A sweep of six points, each a few hundred ms, to interrupt.
cp "$FTI" "$tmp/sweep.toml"
sed -i 's/^t_end_ms = .*/t_end_ms = 3000/; s/^discard_ms = .*/discard_ms = 1000/' "$tmp/sweep.toml"
printf '[sweep]\ndesign = "grid"\n[[sweep.parameter]]\nname = "middle.fti.b_v"\nvalues = [10.0, 11.0, 12.0, 13.0, 14.0, 15.0]\n' >>"$tmp/sweep.toml"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$tmp/whole.h5" -q -j 1 || bad "uninterrupted sweep failed"
features() { h5dump -g /sweep "$1" 2>/dev/null | grep -v "^HDF5"; }  # features, status and points of every point
for sig in KILL INT; do
  out="$tmp/$sig.h5"
  "$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 & pid=$!
  for _ in $(seq 100); do [ -s "$out.journal" ] && [ "$(wc -l <"$out.journal")" -ge 3 ] && break; sleep 0.1; done
  kill -$sig $pid; wait $pid; rc=$?
  [ ! -e "$out" ] && ok || bad "SIG$sig: a complete-looking $out exists after the signal"
  [ $rc -ne 0 ] && ok || bad "SIG$sig: exit 0 after the signal"
  "$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 --resume 2>"$tmp/err" || bad "SIG$sig: --resume failed: $(cat "$tmp/err")"
  [ -n "$(features "$out")" ] && [ "$(features "$out")" = "$(features "$tmp/whole.h5")" ] && ok \
    || bad "SIG$sig: --resume differs from the uninterrupted sweep"
done

# SIGKILL during simulate: no output file, at most its temporary. 200 s of model time, so that
# the run is still going when the signal comes however fast the integrator is.
sed 's/^t_end_ms = .*/t_end_ms = 200000/' "$FTI" >"$tmp/long.toml"
"$PHASMID" simulate "$tmp/long.toml" -o "$tmp/sim.h5" -q & pid=$!
sleep 0.5; kill -KILL $pid; wait $pid
[ ! -e "$tmp/sim.h5" ] && ok || bad "SIGKILL simulate: a complete-looking output exists"

# Two writers: the second sweep on a busy output is refused and leaves the first one's journal whole.
out="$tmp/two.h5"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 & pid=$!
for _ in $(seq 100); do [ -s "$out.journal" ] && [ "$(wc -l <"$out.journal")" -ge 2 ] && break; sleep 0.1; done
lines_before=$(wc -l <"$out.journal")
"$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 --resume 2>"$tmp/err"; rc=$?
one_line_error $rc "$tmp/err" "another phasmid sweep is running on this output" && ok || bad "second writer: rc=$rc, stderr: $(cat "$tmp/err")"
[ "$(wc -l <"$out.journal")" -ge "$lines_before" ] && ok || bad "second writer truncated the journal"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 2>"$tmp/err"; rc=$?
one_line_error $rc "$tmp/err" "journal of an unfinished sweep|another phasmid sweep is running" && ok || bad "second writer without --resume: rc=$rc, stderr: $(cat "$tmp/err")"
[ "$(wc -l <"$out.journal")" -ge "$lines_before" ] && ok || bad "second writer without --resume truncated the journal"
wait $pid || bad "the first sweep failed after the second was refused"
[ "$(features "$out")" = "$(features "$tmp/whole.h5")" ] && ok || bad "the first sweep's result differs after a refused second writer"

echo "$pass passed, $fail failed, $skip skipped"
[ $fail -eq 0 ]
