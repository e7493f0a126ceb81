#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Vector3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <boost/array.hpp>

namespace is_graphs {
namespace ros_conversions {

inline geometry_msgs::Pose ToPose(const Eigen::Isometry3d& t) {
  geometry_msgs::Pose p;
  p.position.x = t.translation().x();
  p.position.y = t.translation().y();
  p.position.z = t.translation().z();
  const Eigen::Quaterniond q(t.rotation());
  p.orientation.w = q.w();
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  return p;
}

/// A pose message as an isometry; the quaternion is normalized (a zero quaternion: identity).
inline Eigen::Isometry3d FromPose(const geometry_msgs::Pose& p) {
  Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  q = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = q.toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

inline geometry_msgs::Vector3 ToVector3(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 out;
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
  return out;
}

inline Eigen::Vector3d FromVector3(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

/// Row-major fixed-size message array <-> Eigen matrix.
template <int R, int C, size_t N>
void ToArray(const Eigen::Matrix<double, R, C>& m, boost::array<double, N>& out) {
  static_assert(R * C == static_cast<int>(N), "size mismatch");
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c) out[r * C + c] = m(r, c);
}

template <int R, int C, size_t N>
Eigen::Matrix<double, R, C> FromArray(const boost::array<double, N>& in) {
  static_assert(R * C == static_cast<int>(N), "size mismatch");
  Eigen::Matrix<double, R, C> m;
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c) m(r, c) = in[r * C + c];
  return m;
}

}  // namespace ros_conversions
}  // namespace is_graphs
