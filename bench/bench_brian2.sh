#!/usr/bin/env bash
# phasmid vs Brian2 on the isolated FTi joint network (configs/single_joint_fti.toml, 26
# states) or the middle leg (configs/middle_leg_forward.toml, 78 states), 9 s of model time:
# run time and feature accuracy, one table (docs/performance.md "phasmid vs Brian2").
#
#   bash bench/bench_brian2.sh [REPEATS [MODEL]]   (default 3, single_joint_fti; or middle_leg_forward)
#   PHASMID=path overrides build/phasmid; PHASMID_TOLS, RK4_DTS, GSL_METHODS, GSL_ERRORS, GSL_DT
#   the ladders (GSL_METHODS: Brian2's adaptive GSL pairs, default "rkf45 rkck").
#   The first phasmid row is the config as shipped: its [simulation] has no solver key, so the
#   model kind's default integration runs (docs/solver.md "How each kind integrates"), with its
#   compiled right-hand side; that row's first run, with an empty cache, compiles, and its extra
#   CPU time is the row's "compile s" (children's CPU counts), as Brian2's is.
#   PHASMID_TOLS (default none) and PHASMID_METHODS (default "dopri5 cvodes_bdf"): more rows with
#   [simulation] rtol = atol = TOL and integrator = METHOD, which the kind maps onto its parts.
#
# Every row is checked against a tight-tolerance phasmid reference (rtol = atol = 1e-12):
# the period and the mean extremal angles of every joint over [discard_ms, t_end_ms] =
# [2000, 9000] ms; the table gives the largest error of each kind over the joints. Times are
# CPU seconds of the solve only, minima over REPEATS runs, by the same clock for both tools:
# std::clock around the run, in the process that runs it. Brian2: its standalone run clock
# (around the network run; code generation and compilation reported apart). phasmid: the
# attribute /trajectory cpu_seconds (around the solve: schedule, parts, integration and
# output; start, config, model assembly and the features after it are outside), docs/hdf5.md.
# "process s" is the CPU time of the whole process of one run (phasmid: start, config, solve,
# HDF5 output; Brian2: the compiled binary).
# Last, the head-to-head: HEAD_TO_HEAD rounds (default REPEATS), each runs phasmid's row as
# shipped (the kind's default; H2H_ROW=fastest: the fastest matched phasmid row instead) and then
# every matched Brian2 row once, so that all meet the same load; the
# minima of these runs give the head-to-head ratio against the Brian2 row that is fastest in
# them (the table's rows ran minutes apart, so its fastest Brian2 row is chance).
# Needs Debian's Python with Brian2 (apt-get install -y python3-brian python3-numpy
# libgsl-dev) and h5dump (hdf5-tools).
set -euo pipefail
REPEATS=${1:-3}
MODEL=${2:-single_joint_fti}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PHASMID=${PHASMID:-$ROOT/build/phasmid}
PY=/usr/bin/python3
BRIAN=$ROOT/bench/brian2/$MODEL.py
CONFIG=$ROOT/configs/$MODEL.toml
case $MODEL in
  single_joint_fti) JOINTS="fti" ;;
  middle_leg_forward) JOINTS="thc ctr fti" ;;
  *) echo "bench_brian2: unknown model '$MODEL' (single_joint_fti or middle_leg_forward)" >&2; exit 1 ;;
esac
if grep -Eq '^(rtol|atol|integrator) *=|^\[simulation\.expert\]' "$CONFIG"; then
  echo "bench_brian2: $CONFIG sets solver keys; the shipped row is meant to run the kind's default" >&2
  exit 1
fi
PHASMID_METHODS=${PHASMID_METHODS:-"dopri5 cvodes_bdf"}
PHASMID_TOLS=${PHASMID_TOLS:-}
H2H_ROW=${H2H_ROW:-shipped}
RK4_DTS=${RK4_DTS:-"0.05 0.025 0.01 0.005"}
GSL_ERRORS=${GSL_ERRORS:-"1e-2 1e-3 1e-4 1e-5 1e-6"}
GSL_METHODS=${GSL_METHODS:-"rkf45 rkck"}  # Brian2's adaptive GSL pairs (also rk8pd, rk2; bench/brian2)
GSL_DT=${GSL_DT:-1}  # Brian2 clock dt of the GSL runs, ms (the GSL driver is restarted every dt)
HEAD_TO_HEAD=${HEAD_TO_HEAD:-$REPEATS}
ROW=0  # rows so far: each keeps its own config, cache and Brian2 project for the head-to-head

[ -x "$PHASMID" ] || { echo "bench_brian2: $PHASMID not found (build it: cmake --build build --target phasmid)" >&2; exit 1; }
$PY -c "import brian2, numpy" 2>/dev/null || { echo "bench_brian2: $PY lacks brian2/numpy (apt-get install -y python3-brian python3-numpy libgsl-dev)" >&2; exit 1; }
command -v h5dump >/dev/null || { echo "bench_brian2: h5dump not found (apt-get install -y hdf5-tools)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
ROWS=$TMP/rows.jsonl

# The smallest of the numbers given as arguments.
min_of() { printf '%s\n' "$@" | sort -g | head -1; }

# The solve's CPU time (s) that `phasmid simulate` wrote into H5.
solve_cpu() { h5dump -a /trajectory/cpu_seconds "$1" | awk '/\(0\)/ {print $2}'; }

# Minima over REPEATS runs of `phasmid simulate CFG -o H5`: "process_cpu solve_cpu" (the process's
# CPU time, user + system, and the solve's).
phasmid_cpu() {
  local proc="" solve=""
  for _ in $(seq "$REPEATS"); do
    { TIMEFORMAT='%U %S'; time "$PHASMID" simulate "$1" -o "$2" -q; } 2> "$TMP/time.txt"
    proc+="$(tail -1 "$TMP/time.txt" | awk '{print $1 + $2}') "
    solve+="$(solve_cpu "$2") "
  done
  echo "$(min_of $proc) $(min_of $solve)"
}

# One phasmid row: simulate REPEATS times with integrator METHOD at rtol = atol = TOL (TOL "-":
# the config as shipped), JSON line with times and features. Every row has a compiled-rhs
# cache of its own, so that its first run compiles (reported as "compile s").
phasmid_row() {
  local label=$1 tol=$2 method=${3:-cvodes_bdf}
  ROW=$((ROW + 1))
  local h5=$TMP/phasmid_$ROW.h5 cfg=$TMP/phasmid_$ROW.toml cache=$TMP/rhs-cache-$ROW
  if [ "$tol" = - ]; then
    cp "$CONFIG" "$cfg"
  else
    sed -e "s/^\[simulation\]/[simulation]\nrtol = $tol\natol = $tol\nintegrator = \"$method\"/" "$CONFIG" > "$cfg"
  fi
  local proc solve first="" _
  export PHASMID_CACHE_DIR=$cache
  read -r first _ <<< "$(REPEATS=1 phasmid_cpu "$cfg" "$h5")"
  read -r proc solve <<< "$(phasmid_cpu "$cfg" "$h5")"
  unset PHASMID_CACHE_DIR
  "$PHASMID" features "$h5" --json > "$TMP/features.json"
  $PY - "$label" "$tol" "$proc" "$solve" "$TMP/features.json" "$first" "$cfg" "$cache" >> "$ROWS" <<'EOF2'
import json, sys
label, tol, proc, solve, fj, first, cfg, cache = sys.argv[1:]
f = {x["name"][len("middle."):]: x["value"] for x in json.load(open(fj)) if x["name"].startswith("middle.")}
row = {"tool": "phasmid", "label": label, "tol": None if tol == "-" else float(tol),
       "run_s": float(solve), "process_s": float(proc), "features": f, "config": cfg, "cache": cache}
if first:
    row["compile_s"] = max(0.0, float(first) - float(proc))
print(json.dumps(row))
EOF2
}

# One Brian2 row: compile once, run REPEATS times; the project stays for the head-to-head.
brian_row() {
  local label=$1; shift
  local out dir
  ROW=$((ROW + 1))
  dir=$TMP/brian2_$ROW
  if out=$($PY "$BRIAN" --repeats "$REPEATS" --dir "$dir" "$@" 2> "$TMP/brian2.log" | tail -1); then :; fi
  [ -n "$out" ] || out='{"error": "failed (see the log)"}'
  $PY - "$label" "$out" "$dir" >> "$ROWS" <<'EOF2'
import json, sys
label, out, d = sys.argv[1:]
r = json.loads(out)
row = {"tool": "brian2", "label": label, "project": d}
if "error" in r:
    row["error"] = r["error"]
else:
    row.update(run_s=r["run_cpu_s_min"], process_s=min(r["process_cpu_s"]), compile_s=r["compile_s"],
               features={k: v for k, v in r.items() if "." in k})
print(json.dumps(row))
EOF2
}

# The head-to-head: phasmid's config CFG (with its compiled-rhs CACHE, or "") and each Brian2
# project of the file PROJECTS (one "directory<TAB>label" a line) run in turn, HEAD_TO_HEAD
# rounds; prints "phasmid_min" and then one "brian2_min<TAB>label" line per project (CPU s, as
# in the table). Every matched Brian2 row takes part: which is fastest is decided by the paired
# runs, not by the table, whose rows ran minutes apart.
head_to_head() {
  local cfg=$1 cache=$2 projects=$3 p b dir label pm=""
  : > "$TMP/h2h_brian2.txt"
  for _ in $(seq "$HEAD_TO_HEAD"); do
    [ -n "$cache" ] && export PHASMID_CACHE_DIR=$cache
    "$PHASMID" simulate "$cfg" -o "$TMP/head_to_head.h5" -q
    p=$(solve_cpu "$TMP/head_to_head.h5")
    unset PHASMID_CACHE_DIR
    pm+="$p "
    while IFS=$'\t' read -r dir label; do
      (cd "$dir" && ./main < /dev/null > results/stdout.txt) || { echo "bench_brian2: Brian2's binary in $dir failed" >&2; exit 1; }
      b=$(awk '{print $1}' "$dir/results/last_run_info.txt")
      printf '%s\t%s\n' "$b" "$label" >> "$TMP/h2h_brian2.txt"
    done < "$projects"
  done
  min_of $pm
  sort -t$'\t' -k2,2 -k1,1g "$TMP/h2h_brian2.txt" | awk -F'\t' '$2 != last {print; last = $2}'
}

echo "bench_brian2: reference (phasmid, CVODES BDF on the whole system, rtol = atol = 1e-12) ..." >&2
REPEATS_SAVED=$REPEATS; REPEATS=1
phasmid_row "reference" 1e-12 cvodes_bdf
REPEATS=$REPEATS_SAVED
echo "bench_brian2: phasmid as shipped (the kind's default) ..." >&2
phasmid_row "phasmid as shipped (the kind's default integration)" -
for method in $PHASMID_METHODS; do
  for tol in $PHASMID_TOLS; do
    echo "bench_brian2: phasmid $method rtol = atol = $tol ..." >&2
    phasmid_row "phasmid $method, rtol = atol = $tol" "$tol" "$method"
  done
done
for dt in $RK4_DTS; do
  echo "bench_brian2: Brian2 RK4 dt = $dt ms ..." >&2
  brian_row "Brian2 standalone RK4, dt = $dt ms" --method rk4 --dt "$dt"
done
for m in $GSL_METHODS; do
  for e in $GSL_ERRORS; do
    M=$(echo "$m" | tr a-z A-Z)
    echo "bench_brian2: Brian2 GSL $M absolute error $e ..." >&2
    brian_row "Brian2 standalone GSL $M, abs. error $e (dt = $GSL_DT ms)" --method "$m" --error "$e" --dt "$GSL_DT"
  done
done

$PY - "$ROWS" "$REPEATS" "$MODEL" "$JOINTS" "$TMP/fastest.txt" "$H2H_ROW" <<'EOF'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
open(sys.argv[5], "w").close()
joints = sys.argv[4].split()
ref = rows[0]["features"]
def errors(r):
    """Largest-magnitude period and extremal-angle errors over the joints (None: missing)."""
    f = r.get("features") or {}
    try:
        dp = [f[j + ".period_ms"] - ref[j + ".period_ms"] for j in joints]
        da = [f[j + k] - ref[j + k] for j in joints for k in (".angle_max_deg", ".angle_min_deg")]
    except (KeyError, TypeError):
        return None
    return max(dp, key=abs), max(da, key=abs)
print(f"# bench_brian2: {sys.argv[3]}, 9000 ms, features over 2000-9000 ms, min of {sys.argv[2]} runs;")
print("# run s: CPU time of the solve (std::clock around it; phasmid: /trajectory cpu_seconds)")
print("# reference phasmid rtol = atol = 1e-12: " + "; ".join(
    f"{j} period {ref[j + '.period_ms']:.6f} ms, angles {ref[j + '.angle_min_deg']:.6f} / {ref[j + '.angle_max_deg']:.6f} deg"
    for j in joints))
print("| run | run s | process s | compile s | period err ms | angle err deg | matched |")
print("|---|---:|---:|---:|---:|---:|:---:|")
for r in rows[1:]:
    e = None if "error" in r else errors(r)
    if e is None:
        print(f"| {r['label']} | | | | {r.get('error', 'no features')} | | |")
        continue
    r["ok"] = abs(e[0]) <= 0.01 and abs(e[1]) <= 0.01
    comp = f"{r['compile_s']:.1f}" if "compile_s" in r else ""
    print(f"| {r['label']} | {r['run_s']:.3f} | {r['process_s']:.3f} | {comp} | {e[0]:+.5f} | {e[1]:+.5f} | {'yes' if r['ok'] else 'no'} |")
def fastest(tool):
    c = [r for r in rows[1:] if r["tool"] == tool and r.get("ok")]
    return min(c, key=lambda r: r["run_s"]) if c else None
shipped = next((r for r in rows if r["label"].startswith("phasmid as shipped") and r.get("ok")), None)
pm, bm = fastest("phasmid"), fastest("brian2")
print()
if shipped and bm:
    print(f"phasmid shipped / fastest matched Brian2 ({bm['label']}): {shipped['run_s'] / bm['run_s']:.2f}x the time")
if pm and bm:
    print(f"fastest matched phasmid ({pm['label']}) / fastest matched Brian2: {pm['run_s'] / bm['run_s']:.2f}x the time")
h2h = shipped if sys.argv[6] == "shipped" else pm
if h2h and bm:
    with open(sys.argv[5], "w") as out:
        out.write(f"{h2h['config']} {h2h['cache'] or '-'}\n")
        for r in rows[1:]:
            if r["tool"] == "brian2" and r.get("ok"):
                out.write(f"{r['project']}\t{r['label']}\n")
print("(matched: every period within 0.01 ms and every mean extremal angle within 0.01 deg of the reference; "
      "> 1x: phasmid is slower)")
EOF
if [ -s "$TMP/fastest.txt" ] && [ "$HEAD_TO_HEAD" -gt 0 ]; then
  read -r cfg cache < "$TMP/fastest.txt"
  [ "$cache" = - ] && cache=""
  tail -n +2 "$TMP/fastest.txt" > "$TMP/projects.txt"
  echo "bench_brian2: head-to-head, $HEAD_TO_HEAD rounds of phasmid's $H2H_ROW row and each matched Brian2 row ..." >&2
  head_to_head "$cfg" "$cache" "$TMP/projects.txt" > "$TMP/h2h.txt"
  p=$(head -1 "$TMP/h2h.txt")
  tail -n +2 "$TMP/h2h.txt" | sort -g > "$TMP/h2h_sorted.txt"
  echo "head-to-head, $HEAD_TO_HEAD rounds, phasmid's $H2H_ROW row then each matched Brian2 row, min of each:"
  awk -F'\t' -v p="$p" '{ printf "  phasmid %.3f s, %s %.3f s: %.2fx the time\n", p, $2, $1, p / $1 }' "$TMP/h2h_sorted.txt"
  awk -F'\t' -v p="$p" 'NR == 1 { printf "head-to-head against the fastest matched Brian2 row (%s): %.2fx the time\n", $2, p / $1 }' "$TMP/h2h_sorted.txt"
fi
