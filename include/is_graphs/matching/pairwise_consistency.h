#pragma once

#include <Eigen/Core>

#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/rigid_fit.h"

namespace is_graphs {
namespace matching {

// Pairwise geometric consistency as in CLIPPER: two correspondences are consistent when the
// geometry between their S-Graph nodes equals the geometry between their A-Graph nodes. Only
// quantities no rigid motion changes are compared, and the comparisons are signed (the turn
// from one node to the other), so that a mirror image is inconsistent. Each returns a weight in
// [0, 1]: 0 inconsistent, 1 exactly consistent.

/// A point-normal (a plane's foot point from the room centre and its unit normal).
struct PointNormal {
  Eigen::Vector2d point{Eigen::Vector2d::Zero()};
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};
};

/// Two surface pairs (s1 <-> a1, s2 <-> a2), within a room: the signed angle between the
/// normals and the distance between the points must agree.
double SurfacePairConsistency(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                              const PointNormal& a2, double angle_tolerance_rad,
                              double distance_tolerance);
/// SurfacePairConsistency(...) > 0 with angle_tolerance_rad = acos(cos_angle_tolerance), without
/// the weight's exp or an atan2 (the cosine is computed once by the caller, not per pair).
bool SurfacePairsAgree(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                       const PointNormal& a2, double cos_angle_tolerance,
                       double distance_tolerance);

/// A room-level correspondence for the pairwise test: its centres and the yaw its local fit
/// implies; `axis_free` when the centre is known only across `axis_b` (corridors).
struct RoomCorrespondence {
  Eigen::Vector2d s_centre{Eigen::Vector2d::Zero()};
  Eigen::Vector2d a_centre{Eigen::Vector2d::Zero()};
  double yaw{0.0};
  bool axis_free{false};
  Eigen::Vector2d axis_b{Eigen::Vector2d::UnitX()};
};

/// Two room pairs: yaws agree, and the displacement between the S centres, turned by the yaw,
/// equals the displacement between the A centres (its length is CLIPPER's distance invariant,
/// its direction the signed part), across the axis only where a corridor is involved. The
/// tolerance grows with the distance by `config.lever_arm_slack`.
double RoomPairConsistency(const RoomCorrespondence& i, const RoomCorrespondence& j,
                           const MatcherConfig& config);
/// RoomPairConsistency(...) > 0, without the weights' exp.
bool RoomPairsAgree(const RoomCorrespondence& i, const RoomCorrespondence& j,
                    const MatcherConfig& config);

}  // namespace matching
}  // namespace is_graphs
