#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/merging/is_graph_problem.h"
#include "is_graphs/merging/merger_config.h"

namespace is_graphs {
namespace merging {

/// Whether a solved merge is backed by its match pairs: after a robust solve a wrong match (or a
/// kidnapped robot's new rooms) leaves many pairs far off; a right one leaves most within noise.
struct ConsistencyReport {
  bool consistent{false};
  int surface_inliers{0};
  int surface_pairs{0};
  int room_inliers{0};
  int room_pairs{0};
  double inlier_fraction{0.0};
  double chi2_per_dof{0.0};           // of the inliers
  std::vector<int> outlier_surfaces;  // S-plane ids
  std::vector<int> outlier_rooms;     // S-room ids
  std::string message;                // why not consistent, or a summary
};

/// Gates each pair (config.gate_*), then requires config.min_surface_inliers,
/// config.min_inlier_fraction, config.max_chi2_per_dof and, when `starting` a merge,
/// config.min_room_inliers. A merge already made holds on its surfaces: a room pair that turns
/// outlier later (the S-room redrawn from a worse view, a room changed on site) is dropped, not
/// the merge.
ConsistencyReport CheckConsistency(const MergeSolution& solution, const MergerConfig& config,
                                   bool starting = true);

/// How far apart two B_x_M = (x, y, yaw) put a point p of M: translation [m] and yaw [deg].
struct TransformJump {
  double translation{0.0};
  double yaw_deg{0.0};
};
TransformJump CompareTransforms(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector2d& point_in_map);

/// True when the jump is within config.max_jump_translation and config.max_jump_yaw_deg.
bool TransformsAgree(const TransformJump& jump, const MergerConfig& config);

}  // namespace merging
}  // namespace is_graphs
