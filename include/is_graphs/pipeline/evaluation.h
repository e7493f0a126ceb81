#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace pipeline {

/// Measures of a localization run against its truth (replay_pipeline, `make evaluate`).

/// How far a matched B_x_M (map -> bim) lies from the true one, where it matters: the largest
/// horizontal displacement it gives any of `points` (the S-Graph's keyframe positions in M; the
/// origin of M when empty) against the true transform, and the yaw difference.
struct TransformError {
  double xy_m{0.0};
  double yaw_deg{0.0};
};
TransformError CompareTransforms(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                 const std::vector<Eigen::Vector3d>& points);

/// A wrong match: off by more than `max_xy_m` somewhere on the map or by more than
/// `max_yaw_deg` in yaw.
inline bool IsWrongMatch(const TransformError& e, double max_xy_m = 0.5, double max_yaw_deg = 5.0) {
  return e.xy_m > max_xy_m || e.yaw_deg > max_yaw_deg;
}

/// The map cloud against the BIM (the paper's point-cloud RMSE): points in B against the A-Graph
/// wall-surfaces. A point is used when its orthogonal projection falls on a wall-surface, at
/// least `edge_margin` inside its extent (away from floor, ceiling and the surface's ends:
/// floor and ceiling points near a wall are not wall points), and it lies within
/// `max_distance` of that surface's plane; its error is the distance to the nearest such
/// surface. Points further away (clutter, other storeys, outside, through doors) are left out
/// and counted.
struct CloudErrorConfig {
  double max_distance{0.3};
  double edge_margin{0.1};
};
struct CloudError {
  int points{0};  // all points given
  int used{0};    // within max_distance of a wall-surface
  double rmse{0.0};
  double median{0.0};
  double max{0.0};
  double UsedShare() const { return points > 0 ? static_cast<double>(used) / points : 0.0; }
};
CloudError CloudAgainstWallSurfaces(const std::vector<Eigen::Vector3f>& points_in_bim,
                                    const agraph::AGraph& building,
                                    const CloudErrorConfig& config = {});

}  // namespace pipeline
}  // namespace is_graphs
