#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <random>

#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {

/// One leg-odometry output: base_link in `odom`, the body-frame twist and diagonal variances.
struct OdometrySample {
  double t{0.0};
  Eigen::Isometry3d odom_T_base{Eigen::Isometry3d::Identity()};
  Eigen::Vector3d linear_velocity{Eigen::Vector3d::Zero()};   // in base_link
  Eigen::Vector3d angular_velocity{Eigen::Vector3d::Zero()};  // in base_link
  double variance_xy{0.0};   // m², of x and y (accumulated random walk)
  double variance_yaw{0.0};  // rad²
};

/// Drifting leg odometry from the true motion. The `odom` frame starts on the floor under the
/// start pose, heading along it. Each step integrates the true planar body-frame increment with
/// a scale error, a yaw bias per metre and per second, and random walks (per √m walked) in
/// translation and yaw; roll and pitch are kept true (the IMU observes them), z too unless
/// `z_scale_error` scales each change of height (stairs). Deterministic given the seed; call Step
/// at increasing times. A carry (see Carried) is not seen: the odometry holds its pose across the
/// jump of the truth.
class OdometryDrift {
 public:
  OdometryDrift(const OdometryConfig& config, std::uint64_t seed, double floor_z);

  /// The odometry at time t for the true base_link pose in bim.
  OdometrySample Step(double t, const Eigen::Isometry3d& bim_T_base);
  /// The robot was carried (kidnapped) since the last Step: the legs saw no walking, so the next
  /// Step keeps the odometry's planar pose (zero velocity) and integrates from the new pose on.
  void Carried() { carried_ = started_; }
  /// The odom frame in bim (fixed once the first Step has run).
  const Eigen::Isometry3d& bim_T_odom() const { return bim_T_odom_; }
  /// True distance walked so far, m.
  double distance() const { return distance_; }

 private:
  OdometryConfig config_;
  std::mt19937_64 rng_;
  double floor_z_;
  bool started_{false};
  bool carried_{false};
  double last_t_{0.0};
  Eigen::Vector3d last_true_{Eigen::Vector3d::Zero()};  // planar x, y, yaw in bim
  Eigen::Vector3d odom_{Eigen::Vector3d::Zero()};       // planar x, y, yaw in odom
  Eigen::Isometry3d bim_T_odom_{Eigen::Isometry3d::Identity()};
  double distance_{0.0};
  double odom_height_{0.0};  // z in odom
  double last_z_{0.0};       // true z of the last step
  double variance_xy_{0.0};
  double variance_yaw_{0.0};
};

}  // namespace sim
}  // namespace is_graphs
