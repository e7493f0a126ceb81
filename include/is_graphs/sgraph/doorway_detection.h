#pragma once

#include <string>
#include <vector>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// Doorways from the walked path (FrontendConfig::doorways). Lengths in metres.
struct DoorwayConfig {
  bool detect{true};
  double max_step{1.5};         // longer keyframe steps are scan gaps, not where it walked
  double min_wall_height{1.5};  // lower planes are furniture: walked around, not through
  double extent_margin{0.2};    // a crossing this far beyond a plane's extent still counts
  double max_width{2.5};        // a wider gap is open space, not a doorway
  double merge_distance{0.8};   // crossings closer than this are one doorway
  double wall_band{0.1};        // width: cloud points this near the wall plane ...
  double band_low{0.3};         // ... this high above the floor ...
  double band_high{1.8};        // ... up to this (below a door's head)

  /// Empty when valid, else what is wrong (naming the field as its ROS parameter, doorway_*).
  std::string Validate() const;
};

/// The doorways the walked path went through. A keyframe step (a keyframe and its previous one,
/// at most max_step apart) crosses a wall plane (vertical, at least min_wall_height tall) where
/// it goes from one side of its line to the other, within its extent, or in the gap (at most
/// max_width) between it and a collinear piece of the same wall: the gap is the doorway's width.
/// Crossings within merge_distance of each other (a wall's two faces, the same door walked
/// again) are one doorway at their mean. A doorway joins, on either side of its wall, the S-room
/// nearest to it of those owning a crossed plane (a face along several rooms is a plane of each),
/// and is kept only when there is one: a crossing of planes of no room is not reported.
/// Its width is 0 unless a gap between pieces gave it (see GapWidth for the clouds).
std::vector<Doorway> DetectDoorways(const SGraph& graph, const DoorwayConfig& config);

/// The free gap around a doorway along its wall: `along` holds the coordinates along the wall
/// of the points on it (relative to the crossing point); the width is the distance between the
/// nearest point on either side, or 0 when a side has none or the gap exceeds max_width.
double GapWidth(const std::vector<double>& along, double max_width);

}  // namespace sgraph
}  // namespace is_graphs
