#!/usr/bin/env bash
# Runs two phasmid binaries on the same jobs and compares every numeric HDF5 dataset bit for
# bit (h5diff without tolerance), printing one line per dataset: "identical FILE PATH" or
# "different FILE PATH". Attributes (`created`, `command`) and text datasets (fit summaries
# with wall times) differ by nature and are not compared.
#   scripts/compare_outputs.sh REF_BINARY NEW_BINARY [WORK_DIR] [JOB...]
# A job is a config (`simulate CONFIG`), `sensitivity:CONFIG` (`sensitivity CONFIG`) or `demo`.
# Without jobs: `simulate` on every configs/*.toml whose [model] section has a `type` (the
# Cruse (1980) configs have none), `sensitivity:configs/sensitivity_single_joint.toml` and `demo`.
# Environment: REF_ONLY=1 only writes the reference outputs; SKIP_REF=1 reuses those already in
# WORK_DIR; NEW_SET="NAME=VALUE" passes `--set NAME=VALUE` to the new binary only, to check
# that the comparison reports a change (its datasets then differ); QUIET=1 prints only the
# datasets that differ and the summary.
# Exit status 0 when every dataset is identical.
set -uo pipefail
ref=$(realpath "$1"); new=$(realpath "$2")
cd "$(dirname "$0")/.."
work=${3:-/tmp/phasmid_compare}
shift $(( $# < 3 ? $# : 3 ))
mkdir -p "$work/ref" "$work/new"
command -v h5diff >/dev/null || { echo "h5diff missing: apt-get install hdf5-tools" >&2; exit 2; }

model_configs() {
  for f in configs/*.toml; do
    awk '/^\[model\]/{m=1;next} /^\[/{m=0} m && /^type *=/{found=1} END{exit !found}' "$f" && echo "$f"
  done
}

jobs=("$@")
if [[ ${#jobs[@]} == 0 ]]; then
  mapfile -t jobs < <(model_configs)
  jobs+=("sensitivity:configs/sensitivity_single_joint.toml" demo)
fi

run_jobs() {  # binary, output directory, extra arguments (--set) for every job but demo
  local bin=$1 out=$2 job name
  shift 2
  for job in "${jobs[@]}"; do
    case $job in
      demo)
        "$bin" demo -o "$out/demo" >"$out/log_demo.txt" 2>&1 || echo "$bin demo failed" >&2 ;;
      sensitivity:*)
        name=sensitivity_$(basename "${job#sensitivity:}" .toml)
        "$bin" sensitivity "${job#sensitivity:}" -o "$out/$name.h5" "$@" >"$out/log_$name.txt" 2>&1 ||
          echo "$bin sensitivity ${job#sensitivity:} failed (see $out/log_$name.txt)" >&2 ;;
      *)
        name=simulate_$(basename "$job" .toml)
        "$bin" simulate "$job" -o "$out/$name.h5" "$@" >"$out/log_$name.txt" 2>&1 ||
          echo "$bin simulate $job failed (see $out/log_$name.txt)" >&2 ;;
    esac
  done
}

# Datasets only: every path h5ls lists as a Dataset, compared one by one.
compare_file() {  # ref file, new file
  local a=$1 b=$2 path status=0 rel=${1#"$work/ref/"}
  [[ -f $b ]] || { echo "missing   $rel"; return 1; }
  while read -r path; do
    # Text datasets (fit summaries) carry wall times: only numeric datasets are compared.
    # (The dataset's own type: the first DATATYPE line; its "units" attribute is a string too.)
    h5dump -H -d "$path" "$a" 2>/dev/null | grep -m1 DATATYPE | grep -q H5T_STRING && continue
    if h5diff -q "$a" "$b" "$path" "$path" >/dev/null 2>&1; then
      [[ ${QUIET:-0} == 1 ]] || echo "identical $rel $path"
    else
      echo "different $rel $path"; status=1
    fi
  done < <(h5ls -r "$a" | awk '$2 == "Dataset" {print $1}')
  return $status
}

if [[ ${SKIP_REF:-0} != 1 ]]; then
  rm -rf "$work/ref" && mkdir -p "$work/ref"
  run_jobs "$ref" "$work/ref"
fi
[[ ${REF_ONLY:-0} == 1 ]] && exit 0
rm -rf "$work/new" && mkdir -p "$work/new"
if [[ -n ${NEW_SET:-} ]]; then run_jobs "$new" "$work/new" --set "$NEW_SET"; else run_jobs "$new" "$work/new"; fi
fail=0 files=0
while read -r a; do
  files=$((files + 1))
  compare_file "$a" "$work/new/${a#"$work/ref/"}" || fail=1
done < <(find "$work/ref" -name '*.h5' | sort)
[[ $files == 0 ]] && { echo "no reference outputs in $work/ref"; exit 2; }
[[ $fail == 0 ]] && echo "all datasets identical ($files files)" || echo "some datasets differ"
exit $fail
