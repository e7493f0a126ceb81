#!/usr/bin/env bash
# The main job: global localization of the robot in the BIM on a scenario bag, headless.
#   make demo [SCENARIO=bags/D5_rotated.yaml] [RATE=2] [RVIZ=true]
# Makes the scenario's bag if it is missing or older than its YAML, runs launch/localize.launch
# on it (every node, rosbag play with sim time) recording pose_bim and ground truth, then prints
# the time and distance walked until localized and the APE (evo, no alignment) against ground
# truth, and writes a plot of the trajectory over the BIM plan. Outputs in .ws/demo/<scenario>/.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
export ROS_HOME="${ROS_HOME:-${root}/.ws/ros_home}"
# Everything here runs on this machine: advertise "localhost", not a host name that a bare
# system (a minimal container or chroot) may not resolve. A user's ROS_HOSTNAME/ROS_IP wins.
[ -n "${ROS_IP:-}" ] || export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
scenario="${SCENARIO:-bags/D5_rotated.yaml}"
rate="${RATE:-2}"
rviz="${RVIZ:-false}"
py="${root}/.venv/bin/python3"
# shellcheck source=scripts/scenario_lib.sh
source scripts/scenario_lib.sh
[ -f "${scenario}" ] || { echo "demo: error: no scenario file ${scenario}" >&2; exit 2; }
name="$(basename "${scenario}" .yaml)"
out=".ws/demo/${name}"
mkdir -p "${out}" "${ROS_HOME}"

scenario_bag demo "${scenario}"

scenario_building "${scenario}"
scenario_agraph

# A master of its own, so that the demo never talks to (or kills) a user's roscore.
export ROS_MASTER_URI="http://localhost:${IS_GRAPHS_DEMO_PORT:-11411}"
set +u
# shellcheck disable=SC1091
source .ws/devel/setup.bash
set -u
rm -f "${out}/run.bag" "${out}/run.bag.active"
echo "demo: localizing in $(basename "${building}") on ${bag} at ${rate}x (log: ${out}/roslaunch.log)"
# roslaunch_checked.py: non-zero, naming the node, when a node failed (roslaunch exits 0 then);
# a node that died and was restarted is a warning.
scripts/roslaunch_checked.py --log "${out}/roslaunch.log" -- -p "${ROS_MASTER_URI##*:}" \
  is_graphs localize.launch bim:="${building}" storey:="${storey}" bag:="${root}/${bag}" \
  rate:="${rate}" rviz:="${rviz}" record:="${root}/${out}/run.bag" || {
  echo "demo: the launch failed; the end of ${out}/roslaunch.log:" >&2
  tail -n 30 "${out}/roslaunch.log" >&2
  exit 1
}
for _ in $(seq 1 50); do [ -f "${out}/run.bag" ] && break; sleep 0.1; done
"${py}" scripts/evaluate_run.py "${out}/run.bag" --agraph "${agraph}" --storey "${storey}" \
  --plot "${out}/trajectory.png" --json "${out}/results.json"
# As built against the plan (issue 21): the last `deviations` of the run.
"${py}" scripts/deviation_summary.py "${out}/run.bag"
