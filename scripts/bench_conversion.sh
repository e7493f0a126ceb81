#!/usr/bin/env bash
# Times the IFC -> A-Graph conversion: one line per IFC file with wall time, peak RSS and counts.
#   scripts/bench_conversion.sh [FILE.ifc ...]     (default: ../shared/bim/*.ifc and bim/*.ifc)
set -euo pipefail
export PATH="/usr/bin:/bin:${PATH}"
cd "$(dirname "$0")/.."
PY=.venv/bin/python3
[ -x "$PY" ] || { echo "bench_conversion: error: $PY missing; run scripts/setup.sh" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench_conversion: error: /usr/bin/time missing (apt-get install time)" >&2; exit 1; }
files=("$@")
if ((${#files[@]} == 0)); then
  shopt -s nullglob
  files=(../shared/bim/*.ifc bim/*.ifc)
fi
((${#files[@]})) || { echo "bench_conversion: no IFC files given or found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%-28s %8s %9s  %s\n' file wall_s peak_MiB "storeys surfaces walls rooms doorways warnings"
for f in "${files[@]}"; do
  name=$(basename "$f" .ifc)
  if ! /usr/bin/time -v -o "$tmp/$name.time" "$PY" scripts/ifc_to_agraph.py "$f" -o "$tmp/$name" \
      --quiet >"$tmp/$name.out" 2>"$tmp/$name.err"; then
    printf '%-28s FAILED: %s\n' "$name" "$(tail -n 1 "$tmp/$name.err")"
    continue
  fi
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/{print $2}' "$tmp/$name.time" \
         | awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; printf "%.2f", s }')
  rss=$(awk -F': ' '/Maximum resident set size/{printf "%.0f", $2 / 1024}' "$tmp/$name.time")
  counts=$("$PY" - "$tmp/$name.agraph.json" <<'PYEOF'
import json, sys
g = json.load(open(sys.argv[1]))
print(len(g["storeys"]), len(g["wall_surfaces"]), len(g["walls"]), len(g["rooms"]),
      len(g["doorways"]), len(g["warnings"]))
PYEOF
)
  printf '%-28s %8s %9s  %s\n' "$name" "$wall" "$rss" "$counts"
done
