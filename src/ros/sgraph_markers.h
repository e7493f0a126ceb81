#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace ros_markers {

struct SGraphMarkerStyle {
  std::string frame_id{"map"};
  double layer_spacing{2.5};  // vertical distance between the stacked layers [m]
  double node_scale{0.25};
  double line_width{0.03};
};

/// The S-Graph in layers: keyframes and odometry edges at their poses; wall planes as their
/// mapped extents (translucent quads) and plane nodes one layer up; rooms and
/// corridors a layer above with edges to their planes; the floor on top with edges to the
/// rooms. Namespaces: keyframes, odometry_edges, planes, plane_nodes, observation_edges,
/// rooms, corridors, room_edges, floor, floor_edges.
visualization_msgs::MarkerArray BuildSGraphMarkers(const sgraph::SGraph& graph,
                                                   const SGraphMarkerStyle& style);

}  // namespace ros_markers
}  // namespace is_graphs
