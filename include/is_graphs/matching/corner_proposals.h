#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/matching/surface_evidence.h"

namespace is_graphs {
namespace matching {

/// A wall segment in the plane with the side it faces (free space): an A-Graph wall-surface (in
/// B, normal out of the wall's material) or a wall-grade S-plane (in M, normal towards the
/// sensor).
struct FacingSegment {
  Eigen::Vector2d a{Eigen::Vector2d::Zero()}, b{Eigen::Vector2d::Zero()};
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};  // unit
  int storey{-1};                                    // A-Graph storey (-1 for S-planes)
};

/// Where a segment ends at the line of another, 45° or more from it (a room's corner, a wall
/// meeting a partition, a corridor's end): LiDAR2BIM-style corner descriptors. One pair of
/// corners, one seen and one of the BIM, fixes a planar motion.
struct Corner {
  Eigen::Vector2d point{Eigen::Vector2d::Zero()};    // where the two lines meet
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};  // of the segment that ends there
  Eigen::Vector2d along{Eigen::Vector2d::UnitY()};   // from the corner into that segment
  Eigen::Vector2d other{Eigen::Vector2d::UnitY()};   // normal of the segment it meets
  int storey{-1};
};

/// The corners of `segments`: segment i ends within `reach` of where its line meets the line of
/// segment j (normals 45° or more apart, on the same storey), and that point lies within `reach`
/// of j's extent. Segments shorter than 2 x reach give no corner.
std::vector<Corner> FindCorners(const std::vector<FacingSegment>& segments, double reach);

/// The A-Graph's wall-surfaces as facing segments, on their storey and on the storeys of the
/// rooms they bound (as SurfaceEvidence counts them).
std::vector<FacingSegment> FacingSurfaces(const agraph::AGraph& graph);
/// Wall-grade S-planes as facing segments.
std::vector<FacingSegment> FacingWalls(const std::vector<WallSegment>& walls);

/// A planar motion bim_T_map proposed by corner pairs, and how many pairs proposed it.
struct MotionProposal {
  Pose2 pose;
  int storey{-1};
  int votes{0};
};

/// Every motion that maps a seen corner onto a BIM corner (normals and directions within
/// `angle_tolerance_deg`), those within 0.25 m and 2° of one another counted as one (votes
/// summed, the pose of the first). Sorted by votes, then deterministically by pose. More than
/// `max_distinct` distinct motions: none (too little seen to tell them apart), *too_many set.
std::vector<MotionProposal> ProposeMotions(const std::vector<Corner>& seen,
                                           const std::vector<Corner>& bim,
                                           double angle_tolerance_deg, int max_distinct = 1000000,
                                           bool* too_many = nullptr);

}  // namespace matching
}  // namespace is_graphs
