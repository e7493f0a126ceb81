#pragma once
// deviation_node's edge: the core's WallDeviation list to msg/WallDeviations.msg and to rviz
// markers (walls coloured by status, a MOVED wall's colour a heat map of its offset; a sphere
// per door or opening coloured by its status).
#include <is_graphs/WallDeviations.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "is_graphs/merging/doorway_status.h"
#include "is_graphs/merging/wall_deviations.h"

namespace is_graphs {
namespace ros_conversions {

is_graphs::WallDeviation ToMsg(const merging::WallDeviation& d);
is_graphs::DoorwayDeviation ToMsg(const merging::DoorwayDeviation& d);

/// One LINE_LIST per status (namespace = the status) and a text per wall off the plan.
/// `heat_max`: the offset (m) drawn full red; a MOVED wall at planned_offset is yellow.
/// And a SPHERE_LIST (namespace "doorways") at the doors and openings: green PRESENT, red CLOSED,
/// grey NOT_SEEN; a text at each CLOSED one.
visualization_msgs::MarkerArray DeviationMarkers(
    const std::vector<merging::WallDeviation>& walls,
    const std::vector<merging::DoorwayDeviation>& doors, const std::string& frame_id,
    double heat_max);

}  // namespace ros_conversions
}  // namespace is_graphs
