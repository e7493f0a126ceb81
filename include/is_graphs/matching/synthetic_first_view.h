#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/synthetic_sgraph.h"

namespace is_graphs {
namespace matching {

/// One keyframe's view of a storey (for the first-keyframe campaign and tests): a 2-D scan from
/// a robot standing in an A-room, cast against the storey's wall-surfaces as built (some moved,
/// turned, windows cut into the façade with the world outside seen through them, clutter boxes
/// in the room), giving the S-Graph of that one keyframe: its slice (the hits, 1 m above
/// base_link) and a wall plane for each surface (or box face) hit along at least
/// min_plane_length, in M = bim_T_map⁻¹ B.
struct FirstViewConfig {
  int room{0};                                                 // index into building.rooms
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};  // the truth (yaw + translation)
  int rays{720};
  double max_range{20.0};
  double range_noise{0.02};      // σ [m]
  double plane_noise_deg{1.0};   // σ of each plane's normal
  double min_plane_length{0.6};  // m of hits on a surface for a plane
  int clutter{0};                // boxes 0.3-1.2 m a side in the robot's room
  int moved_walls{0};            // surfaces hit built off the plan by 0.2-0.35 m ...
  int turned_walls{0};           // ... or turned by up to 15 deg about their middle
  int windows{0};                // 1.2-2.5 m openings in external walls hit, with a façade
                                 // 10-30 m beyond each (a street's other side)
  std::uint64_t seed{1};
};

/// The view, or an S-Graph with no keyframe when the room has no free spot for the robot (0.4 m
/// from every wall). plane_truth holds the A-surface of each plane of a BIM surface.
SyntheticSGraph MakeFirstView(const agraph::AGraph& building, const FirstViewConfig& config);

}  // namespace matching
}  // namespace is_graphs
