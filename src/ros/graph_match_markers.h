#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace ros_markers {

struct GraphMatchMarkerStyle {
  std::string frame_id{"bim"};
  double s_graph_lift{3.5};  // the S-Graph drawn this far above the A-Graph [m] (as the iS-Graph)
  double line_width{0.05};
};

/// Lines between matched A-Graph and S-Graph nodes, all in the BIM frame: the S-Graph is moved
/// there by the match's bim_T_map and lifted by s_graph_lift. Namespaces: room_pairs,
/// surface_pairs (lines), s_rooms (the S-room centres), status (a text). Starts with DELETEALL,
/// so a NONE clears earlier lines.
visualization_msgs::MarkerArray BuildGraphMatchMarkers(const matching::GraphMatch& match,
                                                       const agraph::AGraph& a_graph,
                                                       const sgraph::SGraph& s_graph,
                                                       const GraphMatchMarkerStyle& style);

}  // namespace ros_markers
}  // namespace is_graphs
