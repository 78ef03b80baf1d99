#!/usr/bin/env bash
# The layering docs/architecture.md states ("Layers"), enforced on the code: the table there
# gives each folder a rank; a file may include headers of its own folder and of folders of a
# lower rank, and folders that share a rank do not include each other. Every `#include "a/b"`
# of src/** and python/src/** is checked against that table; each violation is printed as
# "src/a/x.cpp:12: includes higher layer src/b/y.hpp", and so is a folder of src/ that the
# table does not place. Usage: layering.test.sh PHASMID SOURCE_DIR (the binary is not used).
set -u
SRC=$2
doc="$SRC/docs/architecture.md"
declare -A rank
# Rows of the Layers table: "| <rank> | <layer> | `src/a`, `src/b` | ... |".
while IFS='|' read -r _ r _ folders _; do
  r=${r// /}
  [[ $r =~ ^[0-9]+$ ]] || continue
  for f in $(grep -o '`[^`]*`' <<<"$folders" | tr -d '`'); do rank[$f]=$r; done
done < <(sed -n '/^## Layers/,/^## [^L]/p' "$doc")
[ ${#rank[@]} -gt 0 ] || { echo "FAIL: no layer table found under '## Layers' in $doc"; exit 1; }

fail=0
# Every folder of src/ has a layer.
for d in "$SRC"/src/*/; do
  d=${d%/}; d=src/${d##*/}
  [ -n "${rank[$d]:-}" ] || { echo "$d: has no layer in docs/architecture.md (add it to the table)"; fail=1; }
done

# The folder (as the table names it) that holds path $1, relative to the source tree; "" if none.
folder_of() {
  case $1 in
    python/src/*) echo python/src ;;
    src/*/*) local rest=${1#src/}; echo "src/${rest%%/*}" ;;
    *) echo "" ;;
  esac
}

n_checked=0
while IFS= read -r file; do
  rel=${file#"$SRC"/}
  from=$(folder_of "$rel")
  [ -n "${rank[$from]:-}" ] || continue  # reported above
  while IFS=: read -r line text; do
    [[ $text =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*\"([^\"]+)\" ]] || continue
    inc=${BASH_REMATCH[1]}
    [[ $inc == */* ]] || continue  # same folder, or generated (build_info.hpp)
    top=${inc%%/*}
    [ -d "$SRC/src/$top" ] || continue  # not a folder of src/ (a library's header)
    to=src/$top
    n_checked=$((n_checked + 1))
    [ "$to" = "$from" ] && continue
    if [ -z "${rank[$to]:-}" ]; then
      continue  # the folder itself is reported above
    elif [ "${rank[$to]}" -gt "${rank[$from]}" ]; then
      echo "$rel:$line: includes higher layer src/$inc"; fail=1
    elif [ "${rank[$to]}" -eq "${rank[$from]}" ]; then
      echo "$rel:$line: includes src/$inc of the same layer (rank ${rank[$to]}: folders of one layer are independent)"; fail=1
    fi
  done < <(grep -n '#[[:space:]]*include' "$file")
done < <(find "$SRC/src/" "$SRC/python/src/" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.def' \) | sort)

[ "$n_checked" -gt 100 ] || { echo "FAIL: only $n_checked includes of src/ headers found (is SOURCE_DIR right?)"; exit 1; }
[ $fail = 0 ] && echo "ok: $n_checked includes across ${#rank[@]} folders follow the layers of docs/architecture.md"
exit $fail
