#include "is_graphs/merging/odometry_extrapolation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace merging {

OdometryCalibration CalibrateOdometry(const sgraph::SGraph& graph,
                                      const std::map<int, Eigen::Isometry3d>& poses,
                                      const OdometryCalibrationConfig& config) {
  std::map<int, const sgraph::Keyframe*> by_id;
  for (const auto& k : graph.keyframes) by_id[k.id] = &k;
  auto pose = [&](const sgraph::Keyframe& k) {
    const auto it = poses.find(k.id);
    return it != poses.end() ? it->second : k.pose;
  };
  struct Step {
    double opt, odom, dyaw;
  };
  std::vector<Step> steps;
  for (const auto& k : graph.keyframes) {
    const auto prev = by_id.find(k.previous);
    if (k.previous < 0 || prev == by_id.end()) continue;
    const Eigen::Isometry3d odom = prev->second->odom_pose.inverse() * k.odom_pose;
    const Eigen::Isometry3d opt = pose(*prev->second).inverse() * pose(k);
    const double d_odom = odom.translation().head<2>().norm();
    const double d_opt = opt.translation().head<2>().norm();
    if (!std::isfinite(d_odom) || !std::isfinite(d_opt) || d_odom < config.min_step) continue;
    steps.push_back(
        {d_opt, d_odom, geometry::NormalizeAngle(geometry::Yaw(opt) - geometry::Yaw(odom))});
  }
  OdometryCalibration out;
  const int n = static_cast<int>(steps.size());
  if (n < config.min_steps) return out;
  double dot = 0.0, sq = 0.0, yaw = 0.0;
  for (int i = std::max(0, n - config.window); i < n; ++i) {
    dot += steps[i].opt * steps[i].odom;
    sq += steps[i].odom * steps[i].odom;
    yaw += steps[i].dyaw * steps[i].odom;
    ++out.steps;
  }
  const double prior = std::max(0.0, config.prior_weight);
  out.scale = std::clamp((dot + prior) / (sq + prior), 1.0 - config.max_scale_error,
                         1.0 + config.max_scale_error);
  out.yaw_per_m = std::clamp(yaw / (sq + prior), -config.max_yaw_per_m, config.max_yaw_per_m);
  return out;
}

Eigen::Isometry3d OdometryAnchor::Pose(const Eigen::Isometry3d& odom_T_base) const {
  Eigen::Isometry3d step = odom_T_keyframe.inverse() * odom_T_base;
  const double d = step.translation().head<2>().norm();
  const double turn = calibration.yaw_per_m * d;
  step.translation().head<2>() =
      Eigen::Rotation2Dd(0.5 * turn) * (calibration.scale * step.translation().head<2>());
  step.linear() =
      Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix() * step.linear();
  return bim_T_keyframe * step;
}

}  // namespace merging
}  // namespace is_graphs
