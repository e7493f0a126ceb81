#!/usr/bin/env bash
# Runs bench_sgraph over the scenario bags present (bags/<name>.bag next to bags/<name>.yaml)
# and prints one table row per bag (`make bench-sgraph`). The full output of each run goes to
# $OUT_DIR/<name>.txt.
#
#   scripts/bench_sgraph.sh [NAME_GLOB...]      e.g. scripts/bench_sgraph.sh 'D?_*' '!*_short'
#
# A pattern starting with '!' excludes. Environment:
#   BENCH_SGRAPH   the bench_sgraph binary (default: .ws/devel/lib/is_graphs/bench_sgraph)
#   BENCH_ARGS     extra arguments, e.g. "--keyframe-distance 0.2"
#   OUT_DIR        where the logs go (default: .ws/bench_sgraph)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
root="$(pwd)"
bench="${BENCH_SGRAPH:-${root}/.ws/devel/lib/is_graphs/bench_sgraph}"
out_dir="${OUT_DIR:-${root}/.ws/bench_sgraph}"
if [ ! -x "${bench}" ]; then
  echo "bench_sgraph: ${bench} not found; build first (make build) or set BENCH_SGRAPH" >&2
  exit 2
fi
mkdir -p "${out_dir}"
patterns=("$@")
[ ${#patterns[@]} -eq 0 ] && patterns=("*")

field() {  # field KEY FILE: a top-level scalar of a scenario YAML
  sed -n "s/^$1:[[:space:]]*//p" "$2" | sed 's/[[:space:]]*#.*//; s/^"//; s/"$//' | head -n1
}

printf '| bag | keyframes | scan median / p99 [ms] | keyframe scan p99 [ms] | optimization median / max [ms] | RTF | peak RSS [MiB] | APE S-Graph / odom [m] | planes within 5 cm & 1 deg (on other elements) | dist. median / max [m] | angle median / max [deg] | rooms walked / found / false | map RMSE S-Graph alone [m] |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
ran=0 failed=0
for yaml in bags/*.yaml; do
  name="$(basename "${yaml}" .yaml)"
  bag="bags/${name}.bag"
  [ -f "${bag}" ] || continue
  match=0
  for p in "${patterns[@]}"; do
    if [[ "${p}" == '!'* ]]; then
      # shellcheck disable=SC2053
      [[ "${name}" == ${p:1} ]] && match=0 && break
    else
      # shellcheck disable=SC2053
      [[ "${name}" == ${p} ]] && match=1
    fi
  done
  [ "${match}" -eq 1 ] || continue
  building="$(field building "${yaml}")"
  storey="$(field storey "${yaml}")"
  args=("${bag}" --building "${building}")
  [ -n "${storey}" ] && args+=(--storey "${storey}")
  log="${out_dir}/${name}.txt"
  # shellcheck disable=SC2086
  if ! "${bench}" "${args[@]}" ${BENCH_ARGS:-} > "${log}" 2>&1; then
    echo "| ${name} | failed: see ${log} |"
    failed=$((failed + 1))
    continue
  fi
  ran=$((ran + 1))
  awk -v name="${name}" '
    /^scans:/ { kf = $4; sub(",", "", kf) }
    /^per-scan latency/ { med = $5; p99 = $7; kp99 = $15; sub(",", "", med); sub(",", "", p99); sub("\\)", "", kp99) }
    /^optimization/ { omed = $4; omax = $6; sub(",", "", omed); sub(";", "", omax) }
    /^real-time factor/ { rtf = $3 }
    /^peak RSS/ { rss = $3 }
    /^trajectory APE/ { ape = $8; odom = $11; sub(",", "", odom) }
    /^wall planes/ {
      match($0, /on other elements: [0-9]+/); win = substr($0, RSTART + 19, RLENGTH - 19)
      match($0, /on a BIM wall-surface: [0-9]+/); on = substr($0, RSTART + 23, RLENGTH - 23)
      match($0, /1 deg: [0-9]+/); good = substr($0, RSTART + 7, RLENGTH - 7)
      match($0, /distance median [0-9.]+ max [0-9.]+/); split(substr($0, RSTART, RLENGTH), d, " ")
      match($0, /angle median [0-9.]+ max [0-9.]+/); split(substr($0, RSTART, RLENGTH), a, " ")
    }
    /^map cloud vs BIM/ { rmse = $13 }
    /^rooms:/ { walked = $4; found = $6; falses = $10; sub(",", "", walked); sub(",", "", found) }
    END {
      printf "| %s | %s | %s / %s | %s | %s / %s | %s | %s | %s / %s | %s / %s (%s) | %s / %s | %s / %s | %s / %s / %s | %s |\n",
        name, kf, med, p99, kp99, omed, omax, rtf, rss, ape, odom, good, on, win, d[3], d[5], a[3], a[5], walked, found, falses, rmse
    }' "${log}"
done
echo
echo "bench_sgraph: ${ran} bags, ${failed} failed; logs in ${out_dir}"
[ "${failed}" -eq 0 ]
