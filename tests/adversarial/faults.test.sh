#!/usr/bin/env bash
# Faults of the adversarial corpus (docs/reliability.md): a full disk, a read-only directory,
# SIGKILL and SIGINT in the middle of a run, two writers on one output. Usage:
# faults.test.sh PHASMID SOURCE_DIR. Mounting a tmpfs needs root; without it those cases skip.
# Nothing here assumes how fast phasmid runs: a signal is sent once there is a sign that the
# run is under way (journal records, the output's temporary file), with far more work left
# than was seen done. HANG_SECONDS only catches a run that shows no sign at all.
set -u
HANG_SECONDS=${HANG_SECONDS:-300}
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
  one_line_error $rc "$tmp/err" "cannot create .*o.h5.tmp" && ok || bad "read-only: rc=$rc, stderr: $(cat "$tmp/err")"
  "$PHASMID" report "$SRC/tests/adversarial/faults.test.sh" -o "$mnt/r.html" 2>"$tmp/err"; rc=$?
  one_line_error $rc "$tmp/err" "not an HDF5 file" && ok || bad "read-only report: rc=$rc, stderr: $(cat "$tmp/err")"
  umount "$mnt"
else
  echo "SKIP: cannot mount a tmpfs (not root?): full disk and read-only directory untested"; skip=$((skip+2))
fi

# A sweep of 51 points of 3000 ms each, to interrupt. The signals come once 3 points are
# journalled (2 in the two-writers case): 48 points still to compute then, against the sign's
# latency of one poll (0.02 s), and the same work per point as the 3 seen done.
n_points=51
cp "$FTI" "$tmp/sweep.toml"
sed -i 's/^t_end_ms = .*/t_end_ms = 3000/; s/^discard_ms = .*/discard_ms = 1000/' "$tmp/sweep.toml"
values=$(awk -v n=$n_points 'BEGIN { for (i = 0; i < n; i++) printf "%s%.1f", (i ? ", " : ""), 10 + i / 10 }')
printf '[sweep]\ndesign = "grid"\n[[sweep.parameter]]\nname = "middle.fti.b_v"\nvalues = [%s]\n' "$values" >>"$tmp/sweep.toml"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$tmp/whole.h5" -q -j 1 || bad "uninterrupted sweep failed"
features() { h5dump -g /sweep "$1" 2>/dev/null | grep -v "^HDF5"; }  # features, status and points of every point
# wait_records OUT N PID WHAT: until OUT's journal holds N point records (its header line aside).
# Fails if the sweep ends first (then the sweep was not interrupted mid-way: this test's premise)
# or shows no such sign within HANG_SECONDS.
wait_records() {
  local journal="$1.journal" end=$((SECONDS + HANG_SECONDS))
  until [ -s "$journal" ] && [ $(($(wc -l <"$journal") - 1)) -ge "$2" ]; do
    kill -0 "$3" 2>/dev/null || { bad "$4: the sweep ended before $2 points were journalled"; return 1; }
    [ $SECONDS -lt $end ] || { bad "$4: hung: fewer than $2 points journalled after $HANG_SECONDS s"; return 1; }
    sleep 0.02
  done
}
for sig in KILL INT; do
  out="$tmp/$sig.h5"
  "$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 & pid=$!
  wait_records "$out" 3 $pid "SIG$sig"
  kill -$sig $pid; wait $pid; rc=$?
  [ ! -e "$out" ] && ok || bad "SIG$sig: a complete-looking $out exists after the signal"
  [ $rc -ne 0 ] && ok || bad "SIG$sig: exit 0 after the signal"
  "$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 --resume 2>"$tmp/err" || bad "SIG$sig: --resume failed: $(cat "$tmp/err")"
  [ -n "$(features "$out")" ] && [ "$(features "$out")" = "$(features "$tmp/whole.h5")" ] && ok \
    || bad "SIG$sig: --resume differs from the uninterrupted sweep"
done

# SIGKILL during simulate: no output file, at most its temporary. A run as long as simulate
# takes (t_end_ms = 1e7, the largest accepted: about 10^4 s of walking, a sample a second,
# around a thousand times the 9 s run), killed as soon as its temporary file exists (the
# samples stream into it as they are reached).
sed 's/^t_end_ms = .*/t_end_ms = 1e7/; s/^output_dt_ms = .*/output_dt_ms = 1000.0/' "$FTI" >"$tmp/long.toml"
"$PHASMID" simulate "$tmp/long.toml" -o "$tmp/sim.h5" -q 2>"$tmp/err" & pid=$!
end=$((SECONDS + HANG_SECONDS))
until [ -e "$tmp/sim.h5.tmp" ] || ! kill -0 $pid 2>/dev/null || [ $SECONDS -ge $end ]; do sleep 0.02; done
if [ -e "$tmp/sim.h5.tmp" ]; then ok
elif kill -0 $pid 2>/dev/null; then bad "SIGKILL simulate: hung: no $tmp/sim.h5.tmp after $HANG_SECONDS s"
else bad "SIGKILL simulate: the run ended before its temporary file appeared: $(cat "$tmp/err")"; fi
kill -KILL $pid; wait $pid; rc=$?
[ $rc -eq 137 ] && ok || bad "SIGKILL simulate: exit $rc, not killed"
[ ! -e "$tmp/sim.h5" ] && ok || bad "SIGKILL simulate: a complete-looking output exists"

# Two writers: the second sweep on a busy output is refused (its output lock, before the journal
# is opened: tests/adversarial/writers.test.sh has the concurrent pairs) and leaves the first
# one's journal whole. The first is stopped (SIGSTOP: it keeps its lock and its journal open) while the others
# try, so that it is mid-sweep then however long they take.
out="$tmp/two.h5"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 & pid=$!
wait_records "$out" 2 $pid "two writers"
kill -STOP $pid
lines_before=$(wc -l <"$out.journal")
"$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 --resume 2>"$tmp/err"; rc=$?
one_line_error $rc "$tmp/err" "is being written by another phasmid process" && ok || bad "second writer: rc=$rc, stderr: $(cat "$tmp/err")"
[ "$(wc -l <"$out.journal")" -ge "$lines_before" ] && ok || bad "second writer truncated the journal"
"$PHASMID" sweep "$tmp/sweep.toml" -o "$out" -q -j 1 2>"$tmp/err"; rc=$?
one_line_error $rc "$tmp/err" "is being written by another phasmid process" && ok || bad "second writer without --resume: rc=$rc, stderr: $(cat "$tmp/err")"
[ "$(wc -l <"$out.journal")" -ge "$lines_before" ] && ok || bad "second writer without --resume truncated the journal"
kill -CONT $pid
wait $pid || bad "the first sweep failed after the second was refused"
[ "$(features "$out")" = "$(features "$tmp/whole.h5")" ] && ok || bad "the first sweep's result differs after a refused second writer"

echo "$pass passed, $fail failed, $skip skipped"
[ $fail -eq 0 ]
