#include "is_graphs/sim/odometry_drift.h"

#include <cmath>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/sim/random.h"

namespace is_graphs {
namespace sim {
namespace {

Eigen::Vector3d Planar(const Eigen::Isometry3d& pose) {
  return {pose.translation().x(), pose.translation().y(), geometry::Yaw(pose)};
}

}  // namespace

OdometryDrift::OdometryDrift(const OdometryConfig& config, std::uint64_t seed, double floor_z)
    : config_(config), rng_(StreamSeed(seed, kStreamOdometry)), floor_z_(floor_z) {}

OdometrySample OdometryDrift::Step(double t, const Eigen::Isometry3d& bim_T_base) {
  const Eigen::Vector3d truth = Planar(bim_T_base);
  OdometrySample sample;
  sample.t = t;
  const bool first = !started_;
  if (!started_) {
    started_ = true;
    bim_T_odom_ = geometry::IsometryFromXYYaw(truth.x(), truth.y(), truth.z(), floor_z_);
  } else if (carried_) {
    carried_ = false;  // no increment: the planar pose holds, the velocity is zero
  } else {
    const double dt = t - last_t_;
    // True increment in the previous body frame.
    const Eigen::Vector2d step = geometry::RotationZ(-last_true_.z()).topLeftCorner<2, 2>() *
                                 (truth.head<2>() - last_true_.head<2>());
    const double dyaw = geometry::NormalizeAngle(truth.z() - last_true_.z());
    const double dist = step.norm();
    std::normal_distribution<double> normal(0.0, 1.0);
    const double sigma_t = config_.translation_random_walk * std::sqrt(dist);
    const double sigma_y = config_.yaw_random_walk * std::sqrt(dist);
    const double nx = normal(rng_), ny = normal(rng_), nyaw = normal(rng_);
    const Eigen::Vector2d measured =
        (1.0 + config_.scale_error) * step + sigma_t * Eigen::Vector2d(nx, ny);
    const double measured_yaw =
        dyaw + config_.yaw_bias_per_m * dist + config_.yaw_bias_per_s * dt + sigma_y * nyaw;
    odom_.head<2>() += geometry::RotationZ(odom_.z()).topLeftCorner<2, 2>() * measured;
    odom_.z() = geometry::NormalizeAngle(odom_.z() + measured_yaw);
    distance_ += dist;
    variance_xy_ += sigma_t * sigma_t;
    variance_yaw_ += sigma_y * sigma_y;
    if (dt > 0.0) {
      sample.linear_velocity = Eigen::Vector3d(measured.x() / dt, measured.y() / dt, 0.0);
      sample.angular_velocity = Eigen::Vector3d(0.0, 0.0, measured_yaw / dt);
    }
  }
  // Height: leg kinematics over stairs misjudge the rise a little (a scale error on each
  // change; without one, the height above the start's floor exactly).
  const double z = bim_T_base.translation().z();
  odom_height_ = config_.z_scale_error == 0.0 || first
                     ? z - floor_z_
                     : odom_height_ + (1.0 + config_.z_scale_error) * (z - last_z_);
  last_z_ = z;
  last_t_ = t;
  last_true_ = truth;
  // Roll and pitch stay true: the body's orientation relative to its own heading.
  const Eigen::Matrix3d tilt = geometry::RotationZ(-truth.z()) * bim_T_base.linear();
  sample.odom_T_base.linear() = geometry::RotationZ(odom_.z()) * tilt;
  sample.odom_T_base.translation() = Eigen::Vector3d(odom_.x(), odom_.y(), odom_height_);
  sample.variance_xy = variance_xy_;
  sample.variance_yaw = variance_yaw_;
  return sample;
}

}  // namespace sim
}  // namespace is_graphs
