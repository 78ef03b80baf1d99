#!/usr/bin/env bash
# Runs two phasmid binaries on the same jobs and compares every numeric HDF5 dataset bit for
# bit (h5diff without tolerance). Attributes (`created`, `command`) and text datasets (fit
# summaries with wall times) differ by nature and are not compared.
#   scripts/compare_outputs.sh REF_BINARY NEW_BINARY [WORK_DIR]
# Jobs: `simulate` on every configs/*.toml whose [model] section has a `type` (the Cruse (1980)
# configs have none), `sensitivity configs/sensitivity_single_joint.toml` and `demo`.
# REF_ONLY=1 only writes the reference outputs; SKIP_REF=1 reuses those already in WORK_DIR.
# Exit status 0 when every dataset is identical.
set -uo pipefail
ref=$(realpath "$1"); new=$(realpath "$2")
cd "$(dirname "$0")/.."
work=${3:-/tmp/phasmid_compare}
mkdir -p "$work/ref" "$work/new"
command -v h5diff >/dev/null || { echo "h5diff missing: apt-get install hdf5-tools" >&2; exit 2; }

model_configs() {
  for f in configs/*.toml; do
    awk '/^\[model\]/{m=1;next} /^\[/{m=0} m && /^type *=/{found=1} END{exit !found}' "$f" && echo "$f"
  done
}

run_jobs() {  # binary, output directory
  local bin=$1 out=$2 f
  for f in $(model_configs); do
    "$bin" simulate "$f" -o "$out/simulate_$(basename "$f" .toml).h5" >"$out/log_$(basename "$f" .toml).txt" 2>&1 ||
      echo "$bin simulate $f failed (see $out/log_$(basename "$f" .toml).txt)" >&2
  done
  "$bin" sensitivity configs/sensitivity_single_joint.toml -o "$out/sensitivity_single_joint.h5" >"$out/log_sensitivity.txt" 2>&1 ||
    echo "$bin sensitivity failed" >&2
  "$bin" demo -o "$out/demo" >"$out/log_demo.txt" 2>&1 || echo "$bin demo failed" >&2
}

# Datasets only: every path h5ls lists as a Dataset, compared one by one.
compare_file() {  # ref file, new file
  local a=$1 b=$2 path status=0
  [[ -f $b ]] || { echo "MISSING $b"; return 1; }
  while read -r path; do
    # Text datasets (fit summaries) carry wall times: only numeric datasets are compared.
    # (The dataset's own type: the first DATATYPE line; its "units" attribute is a string too.)
    h5dump -H -d "$path" "$a" 2>/dev/null | grep -m1 DATATYPE | grep -q H5T_STRING && continue
    if ! h5diff -q "$a" "$b" "$path" "$path" >/dev/null 2>&1; then
      echo "DIFFERS $a $path"; status=1
    fi
  done < <(h5ls -r "$a" | awk '$2 == "Dataset" {print $1}')
  [[ $status == 0 ]] && echo "same    $(basename "$a")"
  return $status
}

[[ ${SKIP_REF:-0} == 1 ]] || run_jobs "$ref" "$work/ref"
[[ ${REF_ONLY:-0} == 1 ]] && exit 0
run_jobs "$new" "$work/new"
fail=0
while read -r a; do
  compare_file "$a" "$work/new/${a#"$work/ref/"}" || fail=1
done < <(find "$work/ref" -name '*.h5' | sort)
[[ $fail == 0 ]] && echo "all datasets identical" || echo "some datasets differ"
exit $fail
