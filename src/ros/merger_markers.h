#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/merging/is_graph_problem.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace ros_markers {

struct MergerMarkerStyle {
  std::string frame_id{"bim"};
  double s_graph_lift{3.5};  // m: the S-Graph layer drawn this far above the A-Graph
};

/// The iS-Graph in the bim frame: the A-Graph (wall-surfaces, room centres), the S-Graph moved
/// by bim_T_map and lifted (planes, room centres, keyframe path) and the match edges between
/// paired rooms and surfaces.
visualization_msgs::MarkerArray BuildMergerMarkers(const agraph::AGraph& a_graph,
                                                   const sgraph::SGraph& s_graph,
                                                   const merging::MatchPairs& pairs,
                                                   const Eigen::Isometry3d& bim_T_map,
                                                   const MergerMarkerStyle& style);

}  // namespace ros_markers
}  // namespace is_graphs
