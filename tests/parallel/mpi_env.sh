# Sourced by the MPI script tests (needs $PHASMID). Skips the test (exit 0 with a note) when
# phasmid was built without MPI or Open MPI's mpirun is missing; lets Open MPI run as root (CI
# containers) for these commands only; moves into a temporary directory removed at exit; and
# gives helpers:
#   ok / bad MESSAGE           count a passed / failed check ($pass, $fail)
#   mpirun_np3 CMD...          CMD on 3 ranks (oversubscribed: CI has 2 cores)
#   rank_pid LAUNCHER_PID R    the pid of rank R started by that mpirun
if ! "$PHASMID" --version | grep -q "MPI compiled in" || ! command -v mpirun >/dev/null || ! command -v h5diff >/dev/null; then
  echo "skipped: phasmid without MPI, or mpirun/h5diff missing"; exit 0
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
mpirun_np3() { mpirun --oversubscribe -np 3 "$@"; }
rank_pid() {
  local p
  for p in $(pgrep -P "$1") $(for c in $(pgrep -P "$1"); do pgrep -P "$c"; done); do
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$2" && { echo "$p"; return; }
  done
}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0; pass=0
ok() { pass=$((pass+1)); }
bad() { echo "FAIL: $*"; fail=$((fail+1)); }
