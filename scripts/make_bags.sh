#!/usr/bin/env bash
# Builds every scenario bags/*.yaml into bags/<name>.bag with make_bag (`make bags`).
#
#   scripts/make_bags.sh [NAME_GLOB...]     e.g. scripts/make_bags.sh '*_short'
#
# Skips bags that are newer than their YAML, their building and make_bag; skips the scenarios
# on ../shared/bim (D1, D2) with a message when that folder is absent. Environment:
#   MAKE_BAG           the make_bag binary (default: .ws/devel/lib/is_graphs/make_bag)
#   BAG_COMPRESSION    none (default), lz4 or bz2
#   FORCE=1            regenerate even when up to date
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
root="$(pwd)"
make_bag="${MAKE_BAG:-${root}/.ws/devel/lib/is_graphs/make_bag}"
if [ ! -x "${make_bag}" ]; then
  echo "make_bags: ${make_bag} not found; build first (make build) or set MAKE_BAG" >&2
  exit 2
fi
patterns=("$@")
[ ${#patterns[@]} -eq 0 ] && patterns=("*")

built=0 skipped=0 failed=0
for yaml in bags/*.yaml; do
  name="$(basename "${yaml}" .yaml)"
  match=0
  for p in "${patterns[@]}"; do
    # shellcheck disable=SC2053
    [[ "${name}" == ${p} ]] && match=1
  done
  [ "${match}" -eq 1 ] || continue
  building="$(sed -n 's/^building:[[:space:]]*//p' "${yaml}" | sed 's/[[:space:]]*#.*//; s/^"//; s/"$//' | head -n1)"
  case "${building}" in /*) building_path="${building}" ;; *) building_path="${root}/${building}" ;; esac
  if [ ! -e "${building_path}" ]; then
    if [[ "${building}" == ../shared/bim/* ]]; then
      echo "make_bags: ${name}: skipped, ${building} is absent (../shared/bim not available)"
      skipped=$((skipped + 1))
      continue
    fi
    echo "make_bags: ${name}: building ${building} not found" >&2
    failed=$((failed + 1))
    continue
  fi
  bag="bags/${name}.bag"
  if [ -z "${FORCE:-}" ] && [ -f "${bag}" ] && [ "${bag}" -nt "${yaml}" ] &&
     [ "${bag}" -nt "${building_path}" ] && [ "${bag}" -nt "${make_bag}" ]; then
    echo "make_bags: ${name}: up to date"
    skipped=$((skipped + 1))
    continue
  fi
  echo "make_bags: ${name}: generating ${bag}"
  start=$(date +%s.%N)
  if "${make_bag}" "${yaml}" -o "${bag}" --quiet --compression "${BAG_COMPRESSION:-none}"; then
    end=$(date +%s.%N)
    printf 'make_bags: %s: done in %.1f s (%s)\n' "${name}" "$(awk -v a="${start}" -v b="${end}" 'BEGIN { print b - a }')" \
      "$(du -h "${bag}" | cut -f1)"
    built=$((built + 1))
  else
    failed=$((failed + 1))
  fi
done
echo "make_bags: ${built} built, ${skipped} skipped, ${failed} failed"
[ "${failed}" -eq 0 ]
