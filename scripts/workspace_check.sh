#!/usr/bin/env bash
# Builds and tests the package the way a user does, in a fresh catkin workspace of its own with
# each of the three build tools (docs/platforms.md, "Your own workspace"):
#
#   scripts/workspace_check.sh [catkin_make] [catkin_build] [colcon]    (default: all three)
#
# For each tool: a new workspace ${WORKSPACE_CHECK_DIR:-/tmp/is_graphs_ws}/TOOL (removed first)
# with a `git clone` of this repository's HEAD in src/is_graphs (so no .venv, no .ws: what a user
# has), the tool's Debian packages installed when missing, a Release build with Debian's Python
# (-DPYTHON_EXECUTABLE=/usr/bin/python3), then the tests:
#   catkin_make   catkin_make; catkin_make run_tests (or the run_tests_is_graphs_* targets of
#                 TESTS); catkin_test_results
#   catkin_build  catkin config --cmake-args ...; catkin build; catkin test (--catkin-test-target
#                 run_tests_is_graphs_* per test of TESTS); catkin_test_results
#   colcon        colcon build --cmake-args ...; colcon test (--ctest-args -R for TESTS);
#                 colcon test-result --verbose
# and prints one table: tool, build ok/failed and minutes, tests passed/failed/skipped and
# minutes. Exit status non-zero when a build fails, a test fails, or a test of TESTS is missing.
#
# TESTS: which tests run, as space-separated extended regular expressions on catkin's test names
# (the part after run_tests_is_graphs_ / _ctest_is_graphs_: gtest_test_core, pytest_make_bag,
# rostest_test_ros_agraph_node.test, rostest_test_ros_localize_D5_rotated_short.test, ...),
# each anchored at its start; every expression must match at least one test. The whole suite,
# TESTS=all, takes about an hour per tool on 2 cores; the default is a representative subset of
# about 10 minutes: the core's gtests, the three pytest suites (skipped with a message naming the
# missing modules without the project's venv), agraph_node's rostest and one scenario rostest.
#
# Other settings: JOBS (make jobs, default 2), WORKSPACE_CHECK_UNCOMMITTED=1 (also apply the
# work tree's uncommitted changes and untracked files to the clone: for trying a change before
# committing it), CMAKE_ARGS (more -D options for all three, e.g. -DIS_GRAPHS_PYTHON=/venv/bin/
# python3). ROS_HOME is the workspace's ros_home/ (logs and caches of one run stay with it).
# Logs: WORKSPACE/{build,test}.log.
set -uo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

repo="$(git -C "$(dirname "$0")" rev-parse --show-toplevel)" || exit 2
head="$(git -C "${repo}" rev-parse HEAD)"  # what every workspace clones
base="${WORKSPACE_CHECK_DIR:-/tmp/is_graphs_ws}"
jobs="${JOBS:-2}"
default_tests='gtest_test_core$ pytest_bim_scripts$ pytest_make_bag$ pytest_rviz_config$
rostest_test_ros_agraph_node\.test$ rostest_test_ros_localize_D5_rotated_short\.test$'
tests="${TESTS:-${default_tests}}"
cmake_args=(-DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3
  -DCATKIN_ENABLE_TESTING=ON)
# shellcheck disable=SC2206
[ -n "${CMAKE_ARGS:-}" ] && cmake_args+=(${CMAKE_ARGS})

tools=("$@")
((${#tools[@]})) || tools=(catkin_make catkin_build colcon)
for t in "${tools[@]}"; do
  case "$t" in
    catkin_make | catkin_build | colcon) ;;
    *) echo "workspace_check: unknown tool '$t' (catkin_make, catkin_build, colcon)" >&2; exit 2 ;;
  esac
done

log() { echo "workspace_check: $*"; }

# The Debian packages each tool comes in (Debian 12 and 13).
tool_packages() {
  case "$1" in
    catkin_make) echo catkin ;;
    catkin_build) echo catkin catkin-tools ;;
    colcon) echo colcon python3-colcon-ros python3-colcon-cmake python3-colcon-test-result \
      python3-colcon-bash python3-colcon-package-selection python3-colcon-parallel-executor ;;
  esac
}

install_tool() {
  local missing=() p
  for p in $(tool_packages "$1"); do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  log "$1: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  if ! apt-cache policy "${missing[@]}" 2>/dev/null | grep -q "Candidate: [0-9]"; then
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq || return 1
  fi
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
}

# A fresh workspace with a clone of HEAD (plus, on request, the uncommitted changes).
make_workspace() {
  local ws="$1"
  rm -rf "${ws}"
  mkdir -p "${ws}/src" "${ws}/ros_home"
  git clone --quiet --no-checkout "${repo}" "${ws}/src/is_graphs" || return 1
  git -C "${ws}/src/is_graphs" checkout --quiet --detach "${head}" ||
    return 1
  if [ "${WORKSPACE_CHECK_UNCOMMITTED:-0}" = 1 ]; then
    git -C "${repo}" diff HEAD --binary | git -C "${ws}/src/is_graphs" apply --allow-empty --whitespace=nowarn ||
      return 1
    (cd "${repo}" && git ls-files --others --exclude-standard -z |
      xargs -0 -r cp --parents -t "${ws}/src/is_graphs") || return 1
  fi
}

# A clean environment: Debian's ROS under /usr, nothing of another workspace (a sourced
# .ws/devel/setup.bash or a pyenv) leaking in.
clean_env() {
  nice env -i HOME="${HOME}" USER="${USER:-root}" LANG=C.UTF-8 TERM=dumb \
    PATH=/usr/bin:/bin:/usr/sbin:/sbin ROS_HOME="$1/ros_home" MAKEFLAGS="-j${jobs}" \
    ${ROS_HOSTNAME:+ROS_HOSTNAME="${ROS_HOSTNAME}"} ${ROS_IP:+ROS_IP="${ROS_IP}"} \
    bash -c "$2"
}

# The test names (after run_tests_is_graphs_ or _ctest_is_graphs_) that TESTS selects, one a
# line, from the list of all on stdin; a pattern matching none is reported on stderr, rc 1.
select_tests() {
  local all rc=0 pattern hits
  all="$(cat)"
  for pattern in ${tests}; do
    hits="$(grep -E "^(${pattern})" <<<"${all}")"
    if [ -z "${hits}" ]; then
      echo "workspace_check: no test matches '${pattern}'" >&2
      rc=1
    else
      echo "${hits}"
    fi
  done | sort -u
  return ${rc}
}

declare -A build_state build_min test_counts test_min
overall=0

minutes() { awk -v s="$1" 'BEGIN { printf "%.1f", s / 60 }'; }

for tool in "${tools[@]}"; do
  ws="${base}/${tool}"
  build_state[$tool]="failed"
  build_min[$tool]="-"
  test_counts[$tool]="-"
  test_min[$tool]="-"
  log "${tool}: workspace ${ws}"
  if ! install_tool "${tool}" || ! make_workspace "${ws}"; then
    build_state[$tool]="no workspace"
    overall=1
    continue
  fi
  q_args="$(printf ' %q' "${cmake_args[@]}")"
  case "${tool}" in
    catkin_make)
      build_cmd="cd '${ws}' && catkin_make -j${jobs}${q_args}"
      results="${ws}/build/test_results"
      list_cmd="make -C '${ws}/build' help | sed -n 's/^\.\.\. run_tests_is_graphs_//p'"
      ;;
    catkin_build)
      build_cmd="cd '${ws}' && catkin init && catkin config --cmake-args${q_args} &&
        catkin build --no-status --no-notify -j${jobs} -p1"
      results="${ws}/build/is_graphs/test_results"
      list_cmd="make -C '${ws}/build/is_graphs' help | sed -n 's/^\.\.\. run_tests_is_graphs_//p'"
      ;;
    colcon)
      build_cmd="cd '${ws}' && colcon build --parallel-workers 1 --event-handlers console_direct+ \
        --cmake-args${q_args}"
      results="${ws}/build/is_graphs/test_results"
      list_cmd="cd '${ws}/build/is_graphs' && ctest -N | sed -n 's/^ *Test *#[0-9]*: _ctest_is_graphs_//p'"
      ;;
  esac
  log "${tool}: building (log ${ws}/build.log)"
  start=$(date +%s)
  clean_env "${ws}" "${build_cmd}" >"${ws}/build.log" 2>&1
  rc=$?
  build_min[$tool]="$(minutes $(($(date +%s) - start)))"
  if [ ${rc} != 0 ]; then
    tail -n 40 "${ws}/build.log"
    log "${tool}: build failed (exit ${rc}), log ${ws}/build.log"
    overall=1
    continue
  fi
  build_state[$tool]="ok"

  # The tests: every one, or those of TESTS.
  selected=""
  if [ "${tests}" != all ]; then
    selected="$(clean_env "${ws}" "${list_cmd}" | select_tests)" || overall=1
    if [ -z "${selected}" ]; then
      test_counts[$tool]="none selected"
      continue
    fi
    log "${tool}: tests $(echo ${selected})"
  fi
  setup="devel/setup.bash"
  [ "${tool}" = colcon ] && setup="install/setup.bash"
  case "${tool}" in
    catkin_make)
      if [ -z "${selected}" ]; then targets="run_tests"; else
        targets="$(sed 's/^/run_tests_is_graphs_/' <<<"${selected}" | tr '\n' ' ')"; fi
      test_cmd="catkin_make -j1 ${targets}${q_args} && catkin_test_results build/test_results"
      ;;
    catkin_build)
      if [ -z "${selected}" ]; then test_cmd="catkin test --no-status --no-notify is_graphs"; else
        test_cmd="true"
        for t in ${selected}; do
          test_cmd+=" && catkin test --no-status --no-notify --catkin-test-target run_tests_is_graphs_$t is_graphs"
        done
      fi
      test_cmd+=" && catkin_test_results build/is_graphs/test_results"
      ;;
    colcon)
      test_cmd="colcon test --packages-select is_graphs --event-handlers console_direct+"
      if [ -n "${selected}" ]; then
        regex="^_ctest_is_graphs_($(sed 's/[.[\*^$]/\\&/g' <<<"${selected}" | paste -sd'|'))\$"
        test_cmd+=" --ctest-args -R '${regex}'"
      fi
      test_cmd+=" ; colcon test-result --test-result-base build/is_graphs --verbose"
      ;;
  esac
  rm -rf "${results}"
  log "${tool}: testing (log ${ws}/test.log)"
  start=$(date +%s)
  clean_env "${ws}" "cd '${ws}' && set +u && source ${setup} && ${test_cmd}" \
    >"${ws}/test.log" 2>&1
  rc=$?
  test_min[$tool]="$(minutes $(($(date +%s) - start)))"
  summary="$(/usr/bin/python3 "${repo}/scripts/test_summary.py" "${results}")"
  summary_rc=$?
  echo "${summary}"
  test_counts[$tool]="$(tail -n 1 <<<"${summary}" | sed 's/^test: //')"
  if [ ${rc} != 0 ] || [ ${summary_rc} != 0 ]; then
    tail -n 30 "${ws}/test.log"
    log "${tool}: tests failed (exit ${rc}), log ${ws}/test.log"
    overall=1
  fi
done

echo
echo "is_graphs ${head:0:7}, $(date -u +%Y-%m-%d), TESTS=$(
  [ "${tests}" = "${default_tests}" ] && echo default || echo "'${tests}'" | tr '\n' ' ')"
printf '| %-12s | %-6s | %9s | %-40s | %8s |\n' tool build "build min" tests "test min"
printf '|%s|%s|%s|%s|%s|\n' --------------  -------- ----------- \
  ------------------------------------------ ----------
for tool in "${tools[@]}"; do
  printf '| %-12s | %-6s | %9s | %-40s | %8s |\n' "${tool}" "${build_state[$tool]}" \
    "${build_min[$tool]}" "${test_counts[$tool]}" "${test_min[$tool]}"
done
exit ${overall}
