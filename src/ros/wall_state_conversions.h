#pragma once
// merger_node's edge for the merge's as-built wall states (issue 21): merging's
// WallDeviationEstimate list to msg/WallDeviationState.msg (ISGraph.wall_states).
#include <is_graphs/WallDeviationState.h>

#include <vector>

#include "is_graphs/merging/is_graph_problem.h"

namespace is_graphs {
namespace ros_conversions {

inline std::vector<is_graphs::WallDeviationState> ToMsg(
    const std::vector<merging::WallDeviationEstimate>& walls) {
  std::vector<is_graphs::WallDeviationState> out;
  out.reserve(walls.size());
  for (const auto& w : walls) {
    is_graphs::WallDeviationState m;
    m.wall_id = w.wall_id;
    m.offset = w.offset;
    m.angle = w.angle;
    m.offset_sigma = w.offset_sigma;
    m.angle_sigma = w.angle_sigma;
    m.pairs = w.pairs;
    out.push_back(m);
  }
  return out;
}

}  // namespace ros_conversions
}  // namespace is_graphs
