#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace ros_markers {

/// How the A-Graph is drawn: wall-surfaces where they are, the wall, room and doorway layers
/// stacked above the building so the layers and the edges between them can be told apart.
struct AGraphMarkerStyle {
  std::string frame_id{"bim"};
  double layer_spacing{2.0};  // vertical distance between stacked layers [m]
  double surface_alpha{0.25};
  double node_scale{0.3};  // sphere diameter of graph nodes [m]
  double line_width{0.03};
  bool draw_names{true};
};

/// All markers of the A-Graph (namespaces: wall_surfaces, surface_outlines, walls, wall_edges,
/// rooms, room_outlines, room_edges, room_names, doorways, doorway_edges).
visualization_msgs::MarkerArray BuildAGraphMarkers(const agraph::AGraph& graph,
                                                   const AGraphMarkerStyle& style);

}  // namespace ros_markers
}  // namespace is_graphs
