#!/usr/bin/env bash
# Sweeps in shards (job arrays without MPI): `sweep --shard i/N` + `merge` give the datasets of
# the whole sweep bit for bit; merge refuses shards of another config, a duplicate shard and an
# incomplete set (naming the missing points and shards) with one line and no output; a shard's
# journal does not resume another shard.
set -u
PHASMID="$1"; SRC="$2"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0; pass=0
source "$SRC/tests/cli/expect_error.sh"
ok() { pass=$((pass+1)); }
bad() { echo "FAIL: $*"; fail=$((fail+1)); }
command -v h5diff >/dev/null || { echo "skipped: h5diff missing (apt-get install hdf5-tools)"; exit 0; }
cfg="$SRC/configs/sweep_fti_mechanics.toml"   # 20 points
"$PHASMID" sweep "$cfg" -o whole.h5 -q -j 2 || bad "whole sweep"
for i in 0 1 2; do "$PHASMID" sweep "$cfg" --shard $i/3 -o part_$i.h5 -q -j 1 || bad "shard $i/3"; done
"$PHASMID" merge part_2.h5 part_0.h5 part_1.h5 -o merged.h5 -q || bad "merge"
h5diff -q whole.h5 merged.h5 /sweep /sweep && h5diff -q whole.h5 merged.h5 /parameters /parameters && ok \
  || bad "merged shards differ from the whole sweep"
[ "$(h5dump -a /sweep/n_points merged.h5 | grep -c '(0): 20')" -eq 1 ] && ok || bad "merged n_points"

expect_error "missing shard" "7 of 20 points missing (1, 4, 7, 10, 13, 16, 19): shard 1/3 not given" \
  "$PHASMID" merge part_0.h5 part_2.h5 -o m1.h5
[ -e m1.h5 ] && bad "output written for an incomplete merge"
"$PHASMID" sweep "$cfg" --shard 1/3 -o other.h5 -q --set middle.fti.b_v=13 || bad "shard of another config"
expect_error "shard of another config" "other.h5: shard of a different sweep than part_0.h5" \
  "$PHASMID" merge part_0.h5 other.h5 part_2.h5 -o m2.h5
expect_error "duplicate shard" "shard 0/3 given twice" "$PHASMID" merge part_0.h5 part_0.h5 -o m3.h5
expect_error "bad --shard" "expected i/N with 0 <= i < N" "$PHASMID" sweep "$cfg" --shard 3/3 -o x.h5
"$PHASMID" sweep "$cfg" --shard 0/2 -o s.h5 -q --stop-after 2 -j 1 2>/dev/null
expect_error "journal of another shard" "belongs to a different sweep" \
  "$PHASMID" sweep "$cfg" --shard 1/2 -o s.h5 -q --resume
"$PHASMID" sweep "$cfg" --shard 0/2 -o s.h5 -q --resume && "$PHASMID" sweep "$cfg" --shard 1/2 -o t.h5 -q \
  && "$PHASMID" merge s.h5 t.h5 -o m4.h5 -q && h5diff -q whole.h5 m4.h5 /sweep /sweep && ok \
  || bad "resumed shard merged"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
