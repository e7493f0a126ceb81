#!/usr/bin/env bash
# One platform's check for `make platforms` (scripts/platforms.sh runs it as root in a fresh
# clone inside each Debian root; it also runs as is on any machine): make setup, make build, the
# core gtests, SCENARIO's bag made and localized. Its last line is the table row:
#   platform-row: | compiler | Ceres | Embree | PCL | Python | build | warnings | gtests | bag | s | m |
#   scripts/platform_check.sh [bags/D5_rotated_short.yaml]
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
scenario="${1:-bags/D5_rotated_short.yaml}"
name="$(basename "${scenario}" .yaml)"
version() { dpkg-query -W -f='${Version}' "$1" 2>/dev/null | sed -E 's/^[0-9]+://; s/[-+~].*//'; }
compiler="$(basename "${CXX:-g++}") $(${CXX:-g++} -dumpfullversion 2>/dev/null)"
row() {
  echo "platform-row: | ${compiler} | $(version libceres-dev) | $(version libembree-dev) |" \
    "$(version libpcl-dev) | $(/usr/bin/python3 -c 'import platform; print(platform.python_version())' 2>/dev/null) |" \
    "$1 |"
}

make setup || { row "setup failed | | | | | |"; exit 1; }
make build || { row "build failed | | | | | |"; exit 1; }
warnings=$(grep -E "warning:" .ws/build.log | sort -u | wc -l)

set +u
# shellcheck disable=SC1091
source .ws/devel/setup.bash
set -u
make -C .ws/build -j"$(nproc)" test_core > .ws/test_core_build.log 2>&1 \
  || { row "ok | ${warnings} | test_core build failed | | | |"; exit 1; }
warnings=$((warnings + $(grep -E "warning:" .ws/test_core_build.log | sort -u | wc -l)))
.ws/devel/lib/is_graphs/test_core > .ws/test_core.log 2>&1
gtest_rc=$?
passed=$(sed -nE 's/^\[  PASSED  \] ([0-9]+) tests?.*/\1/p' .ws/test_core.log | tail -n1)
failed=$(sed -nE 's/^\[  FAILED  \] ([0-9]+) tests?, listed below.*/\1/p' .ws/test_core.log | tail -n1)
gtests="${passed:-0} passed, ${failed:-0} failed"
[ "${gtest_rc}" = 0 ] || grep -E "^\[  FAILED  \]" .ws/test_core.log | sort -u | head -n 20

bag="bags/${name}.bag"
.ws/devel/lib/is_graphs/make_bag "${scenario}" -o "${bag}" --quiet \
  || { row "ok | ${warnings} | ${gtests} | make_bag failed | | |"; exit 1; }
sha=$(sha256sum "${bag}" | cut -c1-12)
out=.ws/platform_eval
.venv/bin/python3 scripts/evaluate.py "${scenario}" --out "${out}" > .ws/platform_eval.log 2>&1 \
  || { tail -n 20 .ws/platform_eval.log; row "ok | ${warnings} | ${gtests} | ${sha} | evaluate failed | |"; exit 1; }
read -r localized ape < <(/usr/bin/python3 - "${out}/results.json" "${name}" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))["datasets"][sys.argv[2]]
s = d.get("seconds_to_localize")
ape = d.get("isgraphs", {}).get("ape_xy_rmse_m")
print(f"{s:.1f}s" if s is not None else "never", f"{ape:.4f}m" if ape is not None else "-")
EOF
)
row "ok | ${warnings} | ${gtests} | ${sha} | ${localized} | ${ape}"
[ "${gtest_rc}" = 0 ]
