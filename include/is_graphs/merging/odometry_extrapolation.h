#pragma once

#include <Eigen/Geometry>
#include <map>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// Leg odometry's systematic errors, as the S-Graph shows them: the optimized step between two
/// keyframes against the odometry's. A scale error (the travelled distance x (1 + e)) and a yaw
/// bias per metre walked make the pose drift between keyframes by the same share of every step:
/// 6 % of a 0.8 m step is 4.8 cm, more than the random walk.
struct OdometryCalibration {
  double scale{1.0};      // optimized distance / odometry distance
  double yaw_per_m{0.0};  // optimized - odometry yaw, rad per metre walked
  int steps{0};           // keyframe steps it was estimated from (0: the identity)
};

struct OdometryCalibrationConfig {
  int window{40};    // the newest keyframe steps used
  int min_steps{2};  // fewer: no calibration (the identity)
  // The identity as a prior, worth this many m² of odometry steps (one perfect 0.7 m step):
  // the first few steps calibrate in part, as soon as a merge starts (the matcher's proposals
  // localize after 2-4 keyframes, when 8 steps were not there yet); 30 steps of 0.8 m keep
  // 97.5 % of the estimate.
  double prior_weight{0.5};
  double min_step{0.3};          // m of odometry: shorter steps (turns on the spot) are left out
  double max_scale_error{0.15};  // the scale is clamped to 1 +- this
  double max_yaw_per_m{0.02};    // rad/m, clamped
};

/// Least squares over the newest `window` steps (keyframe and its previous, both with poses),
/// shrunk to the identity by prior_weight λ: scale = (Σ|d_opt||d_odom| + λ) / (Σ|d_odom|² + λ),
/// yaw_per_m = Σ(θ_opt - θ_odom)|d_odom| / (Σ|d_odom|² + λ).
/// `poses` (keyframe id -> map <- base) overrides the S-Graph's own optimized poses (the merged
/// ones); the odometry steps are the keyframes' odom_pose.
OdometryCalibration CalibrateOdometry(const sgraph::SGraph& graph,
                                      const std::map<int, Eigen::Isometry3d>& poses,
                                      const OdometryCalibrationConfig& config = {});

/// The robot's pose in B between S-Graph revisions: the newest merged keyframe's pose and the
/// odometry since it, its planar translation scaled and its heading turned by the calibration
/// (the heading error grows along the way: half of it turns the translation).
struct OdometryAnchor {
  Eigen::Isometry3d bim_T_keyframe{Eigen::Isometry3d::Identity()};
  Eigen::Isometry3d odom_T_keyframe{Eigen::Isometry3d::Identity()};
  OdometryCalibration calibration;

  /// B <- base_link for an odometry reading odom <- base_link.
  Eigen::Isometry3d Pose(const Eigen::Isometry3d& odom_T_base) const;
};

}  // namespace merging
}  // namespace is_graphs
