#!/usr/bin/env bash
# The README's pictures, made by the project (make screenshot):
#   docs/images/isgraph.png     rviz (config/is_graphs.rviz, under Xvfb) on the demo's bag: the
#                               BIM, the A-Graph, the S-Graph, the match, the iS-Graph, the robot
#   docs/images/trajectory.png  the trajectory over the BIM plan, plotted as make demo plots it
# Runs launch/localize.launch with rviz on SCENARIO's bag (made if missing), waits until the robot
# is localized and SHOT_AT seconds of the bag have played, grabs the screen, lets the bag finish
# and evaluates the run. Non-zero, with a message, when rviz or the pipeline fails.
#   make screenshot [SCENARIO=bags/D5_rotated.yaml] [RATE=1] [SHOT_AT=130] [OUT=docs/images]
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
export ROS_HOME="${ROS_HOME:-${root}/.ws/ros_home}"
[ -n "${ROS_IP:-}" ] || export ROS_HOSTNAME="${ROS_HOSTNAME:-localhost}"
scenario="${SCENARIO:-bags/D5_rotated.yaml}"
rate="${RATE:-1}"
shot_at="${SHOT_AT:-130}"
images="${OUT:-docs/images}"
py="${root}/.venv/bin/python3"
# shellcheck source=scripts/scenario_lib.sh
source scripts/scenario_lib.sh

fail() { echo "screenshot: error: $*" >&2; exit 1; }
for tool in Xvfb import; do
  command -v "${tool}" >/dev/null || fail "${tool} not found (make setup installs xvfb and imagemagick)"
done
[ -x .ws/devel/lib/rviz/rviz ] || command -v rviz >/dev/null || fail "rviz not found (make setup installs it)"
[ -f .ws/devel/setup.bash ] || fail "no build in .ws/ (make build)"
[ -f "${scenario}" ] || fail "no scenario file ${scenario}"
name="$(basename "${scenario}" .yaml)"
out=".ws/screenshot/${name}"
mkdir -p "${out}" "${images}" "${ROS_HOME}"

scenario_bag screenshot "${scenario}"
scenario_building "${scenario}"
scenario_agraph

# A display and a ROS master of our own.
display=""
for n in $(seq 90 199); do
  if [ ! -e "/tmp/.X11-unix/X${n}" ] && [ ! -e "/tmp/.X${n}-lock" ]; then display=":${n}"; break; fi
done
[ -n "${display}" ] || fail "no free X display number"
port="$("${py}" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
export ROS_MASTER_URI="http://localhost:${port}"
xvfb_pid="" launch_pid=""
cleanup() {
  if [ -n "${launch_pid}" ] && kill -0 "${launch_pid}" 2>/dev/null; then
    kill -INT -- "-${launch_pid}" 2>/dev/null || true
    for _ in $(seq 1 40); do kill -0 "${launch_pid}" 2>/dev/null || break; sleep 0.5; done
    kill -KILL -- "-${launch_pid}" 2>/dev/null || true
  fi
  [ -z "${xvfb_pid}" ] || kill "${xvfb_pid}" 2>/dev/null || true
}
trap cleanup EXIT
Xvfb "${display}" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
sleep 1
kill -0 "${xvfb_pid}" 2>/dev/null || fail "Xvfb ${display} did not start"

# The repository's rviz config without its Displays panel: the whole window is the 3-D view.
"${py}" - config/is_graphs.rviz "${out}/screenshot.rviz" <<'PYEOF'
import sys
text = open(sys.argv[1]).read()
start, end = text.index("Panels:\n"), text.index("Visualization Manager:")
open(sys.argv[2], "w").write(text[:start] + "Panels: []\n" + text[end:])
PYEOF

set +u
# shellcheck disable=SC1091
source .ws/devel/setup.bash
set -u
rm -f "${out}/run.bag" "${out}/run.bag.active"
echo "screenshot: rviz on ${bag} in $(basename "${building}") at ${rate}x, shot at ${shot_at} s (log: ${out}/roslaunch.log)"
# roslaunch_checked.py: non-zero, naming the node, when a node failed (roslaunch exits 0 then).
DISPLAY="${display}" setsid scripts/roslaunch_checked.py --log "${out}/roslaunch.log" -- \
  -p "${port}" is_graphs localize.launch bim:="${building}" storey:="${storey}" \
  bag:="${root}/${bag}" rate:="${rate}" rviz:=true rviz_config:="${root}/${out}/screenshot.rviz" \
  record:="${root}/${out}/run.bag" &
launch_pid=$!
for _ in $(seq 1 120); do
  rosnode list >/dev/null 2>&1 && break
  kill -0 "${launch_pid}" 2>/dev/null || { tail -n 20 "${out}/roslaunch.log" >&2; fail "roslaunch ended at start"; }
  sleep 0.5
done
timeout=$(( $(printf '%.0f' "${shot_at}") * 3 / $(printf '%.0f' "${rate}") + 300 ))
if ! /usr/bin/python3 scripts/screenshot_wait.py --shot-at "${shot_at}" --launch-pid "${launch_pid}" \
    --timeout "${timeout}"; then
  tail -n 20 "${out}/roslaunch.log" >&2
  exit 1
fi
rosnode ping -c 1 /rviz >/dev/null 2>&1 || {
  tail -n 20 "${out}/roslaunch.log" >&2
  fail "rviz is not running (see ${out}/roslaunch.log)"
}
import -display "${display}" -window root "${out}/screen.png" || fail "import could not grab ${display}"
echo "screenshot: grabbed ${out}/screen.png; the bag plays to its end"
launch_rc=0
wait "${launch_pid}" || launch_rc=$?
launch_pid=""
[ "${launch_rc}" -eq 0 ] || fail "the launch failed (exit ${launch_rc}, see above and ${out}/roslaunch.log)"
for _ in $(seq 1 50); do [ -f "${out}/run.bag" ] && break; sleep 0.1; done
"${py}" scripts/evaluate_run.py "${out}/run.bag" --agraph "${agraph}" --storey "${storey}" \
  --plot "${out}/trajectory.png" --json "${out}/results.json" | tee "${out}/evaluate.txt"

# The 3-D view without rviz's bars, each layer checked and named in a legend, 256 colours.
"${py}" scripts/screenshot_image.py "${out}/screen.png" "${images}/isgraph.png"
cp "${out}/trajectory.png" "${images}/trajectory.png"
for f in "${images}/isgraph.png" "${images}/trajectory.png"; do
  size=$(stat -c %s "${f}")
  [ "${size}" -lt 512000 ] || fail "${f} is $((size / 1024)) KiB (over 500 KiB)"
  echo "screenshot: wrote ${f} ($((size / 1024)) KiB)"
done
