#!/usr/bin/env bash
# Runs the whole suite (gtest of the core, pytest of the BIM scripts, rostest of the nodes)
# through `catkin_make run_tests`, then catkin_test_results' summary and one closing line
# "test: N passed, N failed, N skipped" (scripts/test_summary.py), after the minutes each group
# of tests took. Non-zero on any failure, on a build failure of the
# tests, and when no test ran at all.
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
export ROS_HOME="${ROS_HOME:-$(pwd)/.ws/ros_home}"
# Everything here runs on this machine: advertise "localhost", not a host name that a bare
# system (a minimal container or chroot) may not resolve. A user's ROS_HOSTNAME/ROS_IP wins.
[ -n "${ROS_IP:-}" ] || export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
mkdir -p "${ROS_HOME}"
rm -rf .ws/build/test_results
started=$(date +%s)
# shellcheck disable=SC1091
set +u  # ROS setup scripts read unset variables
source .ws/devel/setup.bash
set -u
# The test executables and the live tests' bags first, on every core (run_tests makes what is
# missing one job at a time); then the tests, one at a time (the rostests need the cores).
catkin_make -C .ws -j"${IS_GRAPHS_JOBS:-$(nproc)}" tests is_graphs_test_bags \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  > .ws/test.log 2>&1 &&
  catkin_make -C .ws -j1 run_tests -DPYTHON_EXECUTABLE=/usr/bin/python3 >> .ws/test.log 2>&1
make_rc=$?
grep -E "^\[ *(FAILED|SKIPPED) *\]|^(FAILED|ERROR|SKIPPED) |^[0-9]+ (passed|failed)|^(FAILED|ERROR):" \
  .ws/test.log | sort -u || true
echo "-----------------------------------------------------------------------------------------"
catkin_test_results --all .ws/build/test_results > .ws/test_results.txt 2>&1
results_rc=$?
grep -vE "^Skipping" .ws/test_results.txt | tail -n 40
rc=0
if [ "${make_rc}" != 0 ]; then
  echo "test: catkin_make run_tests failed (exit ${make_rc}); see .ws/test.log" >&2
  tail -n 30 .ws/test.log >&2
  rc=1
fi
[ "${results_rc}" != 0 ] && rc=1
/usr/bin/python3 scripts/test_summary.py .ws/build/test_results --wall $(( $(date +%s) - started )) \
  || rc=1
exit ${rc}
