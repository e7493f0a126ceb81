#!/usr/bin/env bash
# Builds the catkin workspace .ws/ (git-ignored) whose only package is this repository.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
root="$(pwd)"
mkdir -p .ws/src
[ -L .ws/src/is_graphs ] || ln -sfn "${root}" .ws/src/is_graphs
jobs="${IS_GRAPHS_JOBS:-$(nproc)}"
catkin_make -C .ws -j"${jobs}" \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_BUILD_TYPE=Release \
  -DCATKIN_ENABLE_TESTING=ON > .ws/build.log 2>&1 || {
  tail -n 60 .ws/build.log >&2
  echo "build: catkin_make failed, full log in .ws/build.log" >&2
  exit 1
}
grep -E "warning:" .ws/build.log | sort -u | head -n 20 >&2 || true
echo "build: ok (.ws/devel)"
