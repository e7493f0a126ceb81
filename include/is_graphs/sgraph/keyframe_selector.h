#pragma once

#include <Eigen/Geometry>
#include <optional>

namespace is_graphs {
namespace sgraph {

/// A new keyframe when the robot walked `distance` or turned `angle_rad` since the last one
/// (odometry poses); the first pose is always one.
class KeyframeSelector {
 public:
  KeyframeSelector(double distance, double angle_rad) : distance_(distance), angle_(angle_rad) {}

  bool IsKeyframe(const Eigen::Isometry3d& odom_pose) const {
    if (!last_) return true;
    const Eigen::Isometry3d delta = last_->inverse() * odom_pose;
    return delta.translation().norm() >= distance_ ||
           Eigen::AngleAxisd(delta.linear()).angle() >= angle_;
  }
  void Accept(const Eigen::Isometry3d& odom_pose) { last_ = odom_pose; }
  void Reset() { last_.reset(); }

 private:
  double distance_;
  double angle_;
  std::optional<Eigen::Isometry3d> last_;
};

}  // namespace sgraph
}  // namespace is_graphs
