#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

// Small SE(2)/SE(3) helpers. The templated ones work with ceres::Jet (they call the math
// functions unqualified so that argument-dependent lookup finds the Jet overloads).

namespace is_graphs {
namespace geometry {

/// Wraps an angle to [-π, π).
template <typename T>
T NormalizeAngle(const T& angle) {
  using std::floor;
  const T two_pi(2.0 * M_PI);
  return angle - two_pi * floor((angle + T(M_PI)) / two_pi);
}

/// The signed turn about z (rad, in (-π, π]) from unit vector `from` to unit vector `to`.
inline double SignedTurn(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  return std::atan2(from.x() * to.y() - from.y() * to.x(), from.dot(to));
}

/// Rotation by `yaw` about z.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationZ(const T& yaw) {
  using std::cos;
  using std::sin;
  const T c = cos(yaw);
  const T s = sin(yaw);
  Eigen::Matrix<T, 3, 3> r;
  r << c, -s, T(0), s, c, T(0), T(0), T(0), T(1);
  return r;
}

/// Yaw of a rotation matrix (the z-y-x Euler angle about z): atan2(R10, R00).
template <typename T>
T Yaw(const Eigen::Matrix<T, 3, 3>& rotation) {
  using std::atan2;
  return atan2(rotation(1, 0), rotation(0, 0));
}

/// Maps a point by the yaw-only transform (x, y, z, yaw): R_z(yaw) p + (x, y, z).
template <typename T>
Eigen::Matrix<T, 3, 1> TransformPointXYYaw(const T& x, const T& y, const T& z, const T& yaw,
                                           const Eigen::Matrix<T, 3, 1>& point) {
  return RotationZ(yaw) * point + Eigen::Matrix<T, 3, 1>(x, y, z);
}

/// The yaw-only SE(3) transform: rotation about z by `yaw`, translation (x, y, z).
inline Eigen::Isometry3d IsometryFromXYYaw(double x, double y, double yaw, double z = 0.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = RotationZ(yaw);
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

inline double Yaw(const Eigen::Isometry3d& pose) { return Yaw(Eigen::Matrix3d(pose.linear())); }

/// (x, y, yaw) of a pose, dropping z, roll and pitch.
inline Eigen::Vector3d ToXYYaw(const Eigen::Isometry3d& pose) {
  return Eigen::Vector3d(pose.translation().x(), pose.translation().y(), Yaw(pose));
}

/// The pose with roll and pitch removed (yaw and translation kept).
inline Eigen::Isometry3d ProjectToYawOnly(const Eigen::Isometry3d& pose) {
  return IsometryFromXYYaw(pose.translation().x(), pose.translation().y(), Yaw(pose),
                           pose.translation().z());
}

}  // namespace geometry
}  // namespace is_graphs
