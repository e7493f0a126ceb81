#!/usr/bin/env bash
# The main job, for now: load the default building (IFC -> A-Graph, cached), build and solve
# its A-Graph factor graph, and print its summary. BIM=path overrides the building.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
export ROS_HOME="${ROS_HOME:-$(pwd)/.ws/ros_home}"
bim="${BIM:-bim/office.ifc}"
exec .ws/devel/lib/is_graphs/agraph_info "${bim}" --cache-dir "${ROS_HOME}/is_graphs/cache"
